// A wall-pressure series against a record (wall_pressure.h): the moving average, the impact and
// second-peak times, the mean error, and the records' CSV.
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "swell/bake/validation/buchner2002.h"
#include "swell/bake/validation/wall_pressure.h"

using namespace swell::bake;
using namespace swell::bake::validation;

namespace {
std::vector<PressurePoint> sampled(double t0, double t1, double dt, double (*f)(double)) {
    std::vector<PressurePoint> out;
    for (double t = t0; t <= t1 + 1e-12; t += dt)
        out.push_back({t, f(t)});
    return out;
}
} // namespace

TEST(WallPressure, MovingAverageTakesTheSamplesWithinTheHalfWidth) {
    const std::vector<PressurePoint> s{{0.0, 0.0}, {1.0, 3.0}, {2.0, 6.0}, {2.5, 0.0}, {10.0, 5.0}};
    const std::vector<PressurePoint> m = movingAverage(s, 1.0);
    ASSERT_EQ(m.size(), s.size());
    EXPECT_DOUBLE_EQ(m[0].p, 1.5);               // t 0: samples at 0 and 1
    EXPECT_DOUBLE_EQ(m[1].p, 3.0);               // t 1: 0, 1, 2
    EXPECT_DOUBLE_EQ(m[2].p, 3.0);               // t 2: 1, 2, 2.5
    EXPECT_DOUBLE_EQ(m[3].p, 3.0);               // t 2.5: 2, 2.5
    EXPECT_DOUBLE_EQ(m[4].p, 5.0);               // t 10: alone
    EXPECT_DOUBLE_EQ(m[2].t, 2.0);               // times are kept
    EXPECT_TRUE(movingAverage({}, 1.0).empty()); // nothing in, nothing out
}

TEST(WallPressure, FiguresReadTheImpactAndTheSecondPeakInItsWindow) {
    // Zero, a step to 0.6 at t = 2.5 and a bump of 0.9 at t = 6.2; a higher spike at 7.5 lies
    // outside the second peak's window and is not taken.
    const auto f = [](double t) {
        double p = t >= 2.5 ? 0.6 : 0.0;
        if (std::abs(t - 6.2) < 0.2)
            p = 0.9;
        if (std::abs(t - 7.5) < 0.2)
            p = 2.0;
        return p;
    };
    const std::vector<PressurePoint> s = sampled(0.0, 8.0, 0.001, f);
    const PressureFigures fig = pressureFigures(s);
    ASSERT_TRUE(fig.impactTime.has_value());
    // The smoothed step first exceeds 0.3 half a window after 2.5 - kPressureSmoothing.
    EXPECT_NEAR(*fig.impactTime, 2.5, 0.002);
    ASSERT_TRUE(fig.peakTime.has_value());
    EXPECT_NEAR(*fig.peakTime, 6.2, 0.16);
    EXPECT_NEAR(fig.peak, 0.9, 1e-9);
    // A series that never rises has neither.
    const PressureFigures flat =
        pressureFigures(sampled(0.0, 4.0, 0.01, [](double) { return 0.1; }));
    EXPECT_FALSE(flat.impactTime.has_value());
    EXPECT_FALSE(flat.peakTime.has_value());
}

TEST(WallPressure, MeanErrorInterpolatesTheReferenceOverItsSpan) {
    const std::vector<PressurePoint> ref = sampled(2.0, 6.0, 0.5, [](double t) { return 0.1 * t; });
    EXPECT_NEAR(*meanAbsPressureError(ref, ref), 0.0, 1e-12);
    // A simulated series 0.05 above a linear reference, sampled between the reference's points
    // and beyond its span (those samples are not compared).
    const std::vector<PressurePoint> sim =
        sampled(0.0, 8.0, 0.01, [](double t) { return 0.1 * t + 0.05; });
    const std::optional<double> e = meanAbsPressureError(sim, ref);
    ASSERT_TRUE(e.has_value());
    EXPECT_NEAR(*e, 0.05, 2e-3); // the averages' ends bend a linear series only slightly
    EXPECT_FALSE(meanAbsPressureError(sampled(7.0, 8.0, 0.1, [](double) { return 0.0; }), ref)
                     .has_value()); // no overlap
}

TEST(WallPressure, RecordsComeOutAsSeriesAndCsv) {
    const std::vector<PressurePoint> exp = buchnerP1Series(&FarWallPressureSample::experiment);
    ASSERT_EQ(exp.size(), buchnerP1Records().size());
    EXPECT_DOUBLE_EQ(exp.front().p, buchnerP1Records().front().experiment);
    const std::vector<PressurePoint> d = buchnerP1Series(&FarWallPressureSample::deltaSph320);
    EXPECT_DOUBLE_EQ(d.back().p, buchnerP1Records().back().deltaSph320);
    // The references' figures (docs/validation.md, Far-wall pressure): delta-SPH's collapse comes
    // later.
    const PressureFigures e = pressureFigures(exp);
    const PressureFigures s = pressureFigures(d);
    ASSERT_TRUE(e.peakTime && s.peakTime && e.impactTime && s.impactTime);
    EXPECT_NEAR(*e.peakTime, 5.87, 0.02);
    EXPECT_NEAR(*s.peakTime, 6.43, 0.02);
    EXPECT_NEAR(*e.impactTime, 2.58, 0.01);
    EXPECT_NEAR(*s.impactTime, 2.60, 0.01);

    const auto columns = buchnerP1Columns();
    ASSERT_EQ(columns.size(), 4u);
    EXPECT_STREQ(columns[0].name, "experiment");
    EXPECT_STREQ(columns[3].name, "delta_sph_320");
    EXPECT_EQ(columns[3].column, &FarWallPressureSample::deltaSph320);

    std::istringstream csv(buchnerP1RecordsCsv());
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "series,t,p");
    int rows = 0, experiment = 0;
    while (std::getline(csv, line)) {
        ++rows;
        experiment += line.rfind("experiment,", 0) == 0 ? 1 : 0;
    }
    EXPECT_EQ(rows, 4 * 525);
    EXPECT_EQ(experiment, 525);
}
