// Regular-wave check (regular_wave.h): fit window, fits against synthetic gauge records made
// from linear theory itself, and the probes CSV reader.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "swell/bake/error.h"
#include "swell/bake/regular_wave.h"
#include "swell/bake/scene.h"
#include "temp_dir.h"

using namespace swell::bake;

namespace {

const std::filesystem::path kScenes = SWELL_SCENES_DIR;

/// Gauge records of a linear progressive wave of height H and wavelength L, sampled every dt.
std::vector<ProbeSample> linearRecord(const Scene& scene, double H, double L, double tEnd,
                                      double dt) {
    const double omega = 2.0 * std::numbers::pi / scene.piston->period;
    const double k = 2.0 * std::numbers::pi / L;
    std::vector<ProbeSample> out;
    for (double t = 0.0; t <= tEnd; t += dt) {
        ProbeSample s;
        s.time = t;
        s.frontX = 1.0;
        for (double x : scene.output.gauges)
            s.elevations.push_back(0.5 * H * std::cos(k * x - omega * t) + 0.003);
        out.push_back(s);
    }
    return out;
}

} // namespace

TEST(RegularWave, WindowOpensAfterTheRampAndArrivalAndClosesBeforeReflections) {
    const Scene scene = loadScene(kScenes / "regular_wave_small.json");
    const WaveWindow w = regularWaveWindow(scene);
    // h = 0.2 m, T = 1.03 s: kh = 1.0, c_g = 0.95 m/s; ramp 2.06 s, farthest gauge 1.1 m.
    EXPECT_GT(w.start, scene.piston->rampTime + 1.1 / 1.0);
    EXPECT_LT(w.start, scene.piston->rampTime + 1.1 / 0.7 + scene.piston->period);
    EXPECT_LE(w.end, scene.run.endTime);
    EXPECT_GT(w.end - w.start, 2.0 * scene.piston->period);
}

TEST(RegularWave, RecoversHeightAndLengthOfALinearWave) {
    const Scene scene = loadScene(kScenes / "regular_wave_small.json");
    const WaveWindow w = regularWaveWindow(scene);
    const RegularWaveCheck exact =
        checkRegularWave(scene, linearRecord(scene, 0.9 * 0.029, 1.26, scene.run.endTime, 0.02), w);
    // A record of 90 % of Biesel's height at the dispersion wavelength reads as such.
    const double L = exact.theory.wavelength;
    const RegularWaveCheck c = checkRegularWave(
        scene, linearRecord(scene, 0.9 * exact.theory.height, L, scene.run.endTime, 0.02), w);
    ASSERT_EQ(c.heights.size(), scene.output.gauges.size());
    for (std::size_t g = 0; g < c.heights.size(); ++g)
        EXPECT_NEAR(c.heightError(g), -0.10, 1e-6) << g;
    EXPECT_NEAR(c.wavelengthError(), 0.0, 1e-6);
    EXPECT_GT(c.samples, 50U);
    EXPECT_NEAR(c.theory.kh, 1.0, 0.005); // dispersion relation at h = 0.2 m, T = 1.03 s
}

TEST(RegularWave, DryGaugeOrRandomPistonIsAClearError) {
    const Scene scene = loadScene(kScenes / "regular_wave_small.json");
    const WaveWindow w = regularWaveWindow(scene);
    auto record = linearRecord(scene, 0.02, 0.9, scene.run.endTime, 0.02);
    for (auto& s : record) {
        if (s.time > w.start + 0.5 && s.time < w.start + 0.6)
            s.elevations[1] = std::nan("");
    }
    EXPECT_THROW(checkRegularWave(scene, record, w), std::invalid_argument);
    const Scene surging = loadScene(kScenes / "surging_small.json");
    EXPECT_THROW(regularWaveWindow(surging), SceneError);
}

TEST(RegularWave, ReadsProbeCsvAndNamesTheLineOfABadValue) {
    const swell::test::TempDir dir("swell_probes_");
    const auto path = dir / "probes.csv";
    {
        std::ofstream f(path);
        f << "time,front_x,gauge_0.5,gauge_0.8\n0,1.5,0.001,nan\n0.02,1.5,0.002,-0.001\n";
    }
    const std::vector<ProbeSample> s = readProbeCsv(path);
    ASSERT_EQ(s.size(), 2U);
    EXPECT_DOUBLE_EQ(s[1].time, 0.02);
    EXPECT_DOUBLE_EQ(s[1].elevations[1], -0.001);
    EXPECT_TRUE(std::isnan(s[0].elevations[1]));
    {
        std::ofstream f(path);
        f << "time,front_x,gauge_0.5\n0,1.5,0.001\n0.02,1.5,abc\n";
    }
    try {
        readProbeCsv(path);
        ADD_FAILURE() << "no error for a bad value";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(":3: 'abc'"), std::string::npos) << e.what();
    }
    {
        std::ofstream f(path);
        f << "time,front_x,gauge_0.5\n0,1.5\n";
    }
    EXPECT_THROW(readProbeCsv(path), std::runtime_error);
    std::filesystem::remove(path);
    EXPECT_THROW(readProbeCsv(path), std::runtime_error);
}
