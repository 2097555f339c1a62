#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "swell/bake/probes.h"

using namespace swell::bake;

namespace {

void addWater(Particles& P, double x, double y, double n) {
    P.add(x, y, ParticleKind::Water);
    P.n.back() = n;
}

} // namespace

TEST(Probes, FrontIsTheLargestNonSplashXAndGaugesReadTheTopParticle) {
    Particles P;
    // A column at x = 0.10 up to y = 0.25, one at x = 0.30 up to 0.05, a splash drop far
    // ahead and high (n below d1 n0 = 4.9), and a wall particle further still.
    for (int j = 0; j < 5; ++j)
        addWater(P, 0.10, 0.05 * j + 0.05, 9.0);
    addWater(P, 0.30, 0.05, 8.0);
    addWater(P, 0.90, 0.80, 1.0);
    P.add(1.0, 0.0, ParticleKind::Wall);
    P.n.back() = 9.0;
    ProbeParams par;
    par.n0 = 10.0;
    par.splashRatio = 0.49;
    par.spacing = 0.02;
    par.stillWaterLevel = 0.2;
    par.gauges = {0.11, 0.30, 0.90, 0.6};
    const ProbeSample s = sampleProbes(P, 1.5, par);
    EXPECT_DOUBLE_EQ(s.time, 1.5);
    EXPECT_DOUBLE_EQ(s.frontX, 0.30); // the splash drop and the wall do not count
    ASSERT_EQ(s.elevations.size(), 4u);
    EXPECT_NEAR(s.elevations[0], 0.25 + 0.01 - 0.2, 1e-12); // top centre + l0/2 - still level
    EXPECT_NEAR(s.elevations[1], 0.05 + 0.01 - 0.2, 1e-12);
    EXPECT_TRUE(std::isnan(s.elevations[2])); // only splash there: dry
    EXPECT_TRUE(std::isnan(s.elevations[3]));
}

TEST(Probes, CsvHeaderAndRows) {
    const std::vector<double> gauges{0.6, 1.25};
    EXPECT_EQ(probeCsvHeader(gauges), "time,front_x,gauge_0.6,gauge_1.25");
    ProbeSample s{0.02, 1.5, {0.0125, std::nan("")}};
    EXPECT_EQ(probeCsvRow(s), "0.02,1.5,0.0125,nan");
}
