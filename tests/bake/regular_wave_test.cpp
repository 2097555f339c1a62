// Regular-wave check (regular_wave.h): fit window, fits against synthetic gauge records made
// from linear theory itself, and the probes CSV reader.
#include <algorithm>
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
#include "swell/bake/wave_theory.h"
#include "temp_dir.h"

using namespace swell::bake;

namespace {

const std::filesystem::path kScenes = SWELL_SCENES_DIR;

/// Gauge records of a linear progressive wave of height H at x = 0 and wavelength L, sampled
/// every dt, whose height decays as exp(-decay x) (decay in 1/m).
std::vector<ProbeSample> linearRecord(const Scene& scene, double H, double L, double tEnd,
                                      double dt, double decay = 0.0) {
    const double omega = 2.0 * std::numbers::pi / scene.piston->period;
    const double k = 2.0 * std::numbers::pi / L;
    std::vector<ProbeSample> out;
    for (double t = 0.0; t <= tEnd; t += dt) {
        ProbeSample s;
        s.time = t;
        s.frontX = 1.0;
        for (double x : scene.output.gauges)
            s.elevations.push_back(0.5 * H * std::exp(-decay * x) * std::cos(k * x - omega * t) +
                                   0.003);
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

// Far gauges (scenes/progressive_wave*.json, three wavelengths): the window opens one period
// after the fully grown wave passed the farthest gauge and closes when the far-wall reflection
// of the piston's first motion reaches that same gauge (the first one it reaches), both at c_g.
TEST(RegularWave, WindowForFarGaugesClosesBeforeTheReflectionReachesTheFarthest) {
    for (const char* name : {"progressive_wave.json", "progressive_wave_deep.json"}) {
        const Scene scene = loadScene(kScenes / name);
        const LinearPistonWave th = linearPistonWave(scene.piston->stroke, scene.piston->period,
                                                     0.2, scene.physics.gravity);
        const double cg = groupVelocity(2.0 * std::numbers::pi / scene.piston->period, 0.2, 9.81);
        const auto& g = scene.output.gauges;
        const double far = *std::max_element(g.begin(), g.end());
        const double near = *std::min_element(g.begin(), g.end());
        EXPECT_GE(far - near, 3.0 * th.wavelength - 1e-3) << name; // at least 3 wavelengths
        const WaveWindow w = regularWaveWindow(scene);
        EXPECT_NEAR(w.start, scene.piston->rampTime + far / cg + scene.piston->period, 1e-9)
            << name;
        const double reflected = (2.0 * scene.geometry.tank->x1 - far) / cg;
        EXPECT_LT(w.end, reflected) << name;
        EXPECT_NEAR(w.end, scene.run.endTime, 1e-12) << name;
        EXPECT_GE(w.end - w.start, 2.0 * scene.piston->period) << name;
        EXPECT_LT(w.end - w.start, 2.5 * scene.piston->period) << name; // end time kept short
        // The h/40 version is the same case at twice the resolution.
        const std::string fine = std::string(name).insert(std::string(name).size() - 5, "_h40");
        const Scene s40 = loadScene(kScenes / fine);
        EXPECT_DOUBLE_EQ(s40.geometry.particleSpacing, 0.005) << fine;
        EXPECT_DOUBLE_EQ(s40.solver.time.dt, 0.5 * scene.solver.time.dt) << fine;
        EXPECT_EQ(s40.output.gauges, g) << fine;
        const WaveWindow w40 = regularWaveWindow(s40);
        EXPECT_DOUBLE_EQ(w40.start, w.start) << fine;
        EXPECT_DOUBLE_EQ(w40.end, w.end) << fine;
    }
    // The deeper case: kh = 1.5 and H/L = 0.035 (Biesel) as its description says.
    const Scene deep = loadScene(kScenes / "progressive_wave_deep.json");
    const LinearPistonWave th =
        linearPistonWave(deep.piston->stroke, deep.piston->period, 0.2, deep.physics.gravity);
    EXPECT_NEAR(th.kh, 1.5, 0.005);
    EXPECT_NEAR(th.steepness, 0.035, 0.001);
    EXPECT_FALSE(th.breaks());
}

// A linear wave whose height decays as exp(-a x) over seven gauges spanning three wavelengths:
// the fits recover the decay per wavelength, the total decay and the wavelength from all gauges.
TEST(RegularWave, FitsDecayAndWavelengthOverAllGauges) {
    Scene scene = loadScene(kScenes / "progressive_wave.json");
    const WaveWindow w = regularWaveWindow(scene);
    const double L = 1.15;     // not the theoretical 1.26 m: the fit must read the record
    const double decay = 0.05; // 1/m
    // Gauge order in the scene must not matter.
    std::reverse(scene.output.gauges.begin(), scene.output.gauges.end());
    const RegularWaveCheck c =
        checkRegularWave(scene, linearRecord(scene, 0.03, L, scene.run.endTime, 0.01, decay), w);
    const auto& g = scene.output.gauges;
    const double span =
        *std::max_element(g.begin(), g.end()) - *std::min_element(g.begin(), g.end());
    EXPECT_NEAR(c.wavelengthFit, L, 1e-6);
    EXPECT_NEAR(c.wavelengthFitError(), L / c.theory.wavelength - 1.0, 1e-6);
    EXPECT_NEAR(c.decayPerWavelength, 1.0 - std::exp(-decay * c.theory.wavelength), 1e-6);
    EXPECT_NEAR(c.decayTotal, 1.0 - std::exp(-decay * span), 1e-6);
    for (std::size_t k = 0; k < g.size(); ++k)
        EXPECT_NEAR(c.heights[k], 0.03 * std::exp(-decay * g[k]), 1e-7) << g[k];
    // No decay: zero. Two gauges: the fit is the two-gauge wavelength.
    const RegularWaveCheck flat =
        checkRegularWave(scene, linearRecord(scene, 0.03, L, scene.run.endTime, 0.01), w);
    EXPECT_NEAR(flat.decayPerWavelength, 0.0, 1e-7);
    EXPECT_NEAR(flat.decayTotal, 0.0, 1e-7);
    scene.output.gauges = {0.5, 1.13};
    const RegularWaveCheck two =
        checkRegularWave(scene, linearRecord(scene, 0.03, L, scene.run.endTime, 0.01), w);
    EXPECT_NEAR(two.wavelengthFit, two.wavelength, 1e-9);
    EXPECT_NEAR(two.wavelength, L, 1e-6);
}

// Linear theory's own record of the ramped piston (linearTheoryRecord): Biesel's height and the
// dispersion wavelength once the wave train has arrived, still water before the fastest
// (shallow-water) waves could arrive, and for the shipped kh = 1.0 case the window and fits
// read it as undamped (measured: heights within 0.63 %, decay 0.00 % per wavelength; the
// kh = 1.5 case reads +4.3 % at the farthest gauge, where the wave front overshoots).
TEST(RegularWave, LinearTheoryRecordOfTheRampedPistonIsBieselsWaveAfterItArrives) {
    const Scene scene = loadScene(kScenes / "progressive_wave.json");
    const WaveWindow w = regularWaveWindow(scene);
    std::vector<double> times;
    for (double t = 0.0; t <= scene.run.endTime; t += 0.01)
        times.push_back(t);
    const std::vector<ProbeSample> rec = linearTheoryRecord(scene, times);
    ASSERT_EQ(rec.size(), times.size());
    const RegularWaveCheck c = checkRegularWave(scene, rec, w);
    for (std::size_t g = 0; g < c.heights.size(); ++g)
        EXPECT_NEAR(c.heightError(g), 0.0, 0.01) << c.gauges[g];
    EXPECT_NEAR(c.decayPerWavelength, 0.0, 0.003);
    EXPECT_NEAR(c.wavelengthFitError(), 0.0, 0.002);
    // Nothing reaches the farthest gauge (4.28 m) before sqrt(g h) = 1.40 m/s could carry it
    // there (3.05 s): at most 0.1 % of the height before 2 s.
    const double H = c.theory.height;
    for (const ProbeSample& s : rec) {
        if (s.time < 2.0) {
            EXPECT_LT(std::abs(s.elevations.back()), 1e-3 * H) << s.time;
        }
    }
    // A scene without a sinusoidal piston is refused like checkRegularWave.
    Scene random = scene;
    random.piston->kind = PistonKind::Random;
    EXPECT_THROW(linearTheoryRecord(random, times), SceneError);
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
