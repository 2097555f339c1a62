// Validation at CI resolution (docs/validation.md has the finer runs and the commands).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "red_noise.h"
#include "swell/bake/bake_driver.h"
#include "swell/bake/error.h"
#include "swell/bake/scene.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/validation/dam_break_run.h"
#include "swell/bake/validation/lobovsky2014.h"
#include "swell/bake/validation/lobovsky_run.h"
#include "swell/bake/validation/regular_wave.h"
#include "swell/bake/validation/shoaling.h"
#include "swell/bake/validation/solitary_wave.h"
#include "swell/bake/validation/standing_wave.h"
#include "swell/bake/validation/still_tank.h"
#include "swell/bake/validation/validation.h"
#include "swell/bake/validation/wall_pressure.h"
#include "swell/bake/validation/wet_dam_break.h"
#include "swell/bake/wave_theory.h"
#include "temp_dir.h"

using namespace swell::bake;
using namespace swell::bake::validation;

namespace {

const std::filesystem::path kScenes = SWELL_SCENES_DIR;

/// Bakes a regular-wave scene with probes into a temporary folder and fits its gauge records
/// in the scene's own windows (what `swell-validate regular-wave` does).
RegularWaveCheck bakeRegularWave(const char* sceneFile) {
    const Scene scene = loadScene(kScenes / sceneFile);
    const swell::test::TempDir dir("swell_wave_");
    BakeOptions opt;
    opt.output = dir / "w.swell";
    opt.probes = dir / "w.csv";
    runBake(scene, opt);
    const std::vector<ProbeSample> samples = readProbeCsv(opt.probes);
    return checkRegularWave(scene, samples, regularWaveWindow(scene),
                            regularWaveGaugeWindows(scene));
}

} // namespace

TEST(Validation, FrontComparisonInterpolatesAndAverages) {
    const std::vector<FrontPoint> sim{{0.0, 1.0}, {1.0, 2.0}, {2.0, 3.0}};
    const std::vector<FrontPoint> exp{{0.5, 1.0}, {1.5, 3.0}, {2.5, 9.0}};
    const FrontError e = compareFront(sim, exp, 0.0, 2.0);
    EXPECT_EQ(e.points, 2);
    EXPECT_NEAR(e.mean, 0.5, 1e-12); // |1.5 - 1| and |2.5 - 3|
    EXPECT_NEAR(e.meanSigned, 0.0, 1e-12);
    EXPECT_NEAR(e.max, 0.5, 1e-12);
    EXPECT_THROW(compareFront(sim, exp, 0.0, 3.0), std::invalid_argument); // 2.5 not covered
}

// alignedFront: a copy of the experiment delayed by a known dT is recovered with error ~0 and
// shift -dT (interpolation between the experimental points is linear, so the copy is exact).
TEST(Validation, AlignedFrontRecoversAKnownShiftWithZeroError) {
    const std::span<const FrontPoint> exp = martinMoyceA225();
    const double dT = 0.137;
    std::vector<FrontPoint> sim{{0.0, 1.0}};
    for (const FrontPoint& p : exp)
        sim.push_back({p.T + dT, p.Z});
    const AlignedFront a = alignedFront(sim, exp, 0.8, 3.0);
    EXPECT_NEAR(a.shift, -dT, 1e-12);
    EXPECT_NEAR(a.error.mean, 0.0, 1e-12);
    EXPECT_NEAR(a.error.max, 0.0, 1e-12);
    EXPECT_EQ(a.error.points, 3); // T = 1.219, 1.997, 2.547; the alignment point 0.832 excluded
    // The raw comparison of the same series sees the delay.
    EXPECT_GT(compareFront(sim, exp, 0.8, 3.0).mean, 0.05);
}

// The crossing is the FIRST one, linearly interpolated, and the shift is not fitted: a series
// that runs ahead by a constant 0.5 in Z keeps an error after alignment.
TEST(Validation, AlignedFrontUsesTheFirstCrossingOfTheFirstPoint) {
    const std::vector<FrontPoint> exp{{1.0, 2.0}, {2.0, 3.0}, {3.0, 4.0}};
    // Crosses Z_1 = 2 between T = 0.5 and 1.0, falls back below it after T = 5 and crosses
    // again between T = 6 and 7 (a later crossing must not be used).
    const std::vector<FrontPoint> sim{{0.0, 1.5}, {0.5, 1.5}, {1.0, 2.5},
                                      {5.0, 6.5}, {6.0, 1.0}, {7.0, 2.5}};
    const AlignedFront a = alignedFront(sim, exp, 0.0, 3.0);
    // Z = 2 between T = 0.5 (1.5) and 1.0 (2.5): T = 0.75, so shift = 1 - 0.75.
    EXPECT_NEAR(a.shift, 0.25, 1e-12);
    EXPECT_EQ(a.error.points, 2);
    // Shifted: T' = T + 0.25; at T' = 2: T = 1.75, Z = 2.5 + 0.75 = 3.25 vs 3.
    EXPECT_NEAR(a.error.mean, 0.25, 1e-12);
    EXPECT_NEAR(a.error.meanSigned, 0.25, 1e-12);
}

// The experiment against itself: the a = 2.25 in record aligned on the a = 1.125 in record's
// first point (Z = 1.245 at T = 0.849). By hand: a = 2.25 in crosses 1.245 at
// T = 0.832 + 0.387 (0.028 / 0.257) = 0.8742, shift -0.0252; at the four a = 1.125 in points
// in [0.8, 3] it is +0.050, +0.019, +0.001 and -0.122 off, mean 0.048 a, max 0.122 a: above
// issue 14's 0.03 a / 0.06 a targets (docs/validation.md section 7).
TEST(Validation, MartinMoyceScatterComparesTheTwoSeriesUnderTheAlignmentRule) {
    const AlignedFront s = martinMoyceScatter(0.8, 3.0);
    EXPECT_NEAR(s.shift, -0.0252, 2e-4);
    EXPECT_EQ(s.error.points, 4);
    EXPECT_NEAR(s.error.mean, 0.048, 1e-3);
    EXPECT_NEAR(s.error.max, 0.122, 1e-3);
    EXPECT_NEAR(s.error.meanSigned, (0.050 + 0.019 + 0.001 - 0.122) / 4.0, 2e-3);
}

TEST(Validation, AlignedFrontRejectsASeriesThatNeverReachesTheFirstPosition) {
    const std::vector<FrontPoint> exp{{1.0, 2.0}, {2.0, 3.0}};
    const std::vector<FrontPoint> slow{{0.0, 1.0}, {3.0, 1.9}, {6.0, 1.99}};
    try {
        alignedFront(slow, exp, 0.0, 3.0);
        ADD_FAILURE() << "no error for a front that never reaches Z_1";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("never reaches"), std::string::npos) << e.what();
    }
    const std::vector<FrontPoint> beyond{{0.0, 2.5}, {3.0, 4.0}};
    EXPECT_THROW(alignedFront(beyond, exp, 0.0, 3.0), std::invalid_argument);
    EXPECT_THROW(alignedFront(std::vector<FrontPoint>{{0.0, 1.0}}, exp, 0.0, 3.0),
                 std::invalid_argument);
}

// spreadOf: an ensemble's figure as mean, sample standard deviation and range.
TEST(Validation, SpreadOfAnEnsembleIsItsMeanSampleDeviationAndRange) {
    const std::vector<double> v{0.074, 0.080, 0.081, 0.075};
    const Spread s = spreadOf(v);
    EXPECT_EQ(s.count, 4u);
    EXPECT_NEAR(s.mean, 0.0775, 1e-15);
    // sum of squares 0.0035^2 + 0.0025^2 + 0.0035^2 + 0.0025^2 = 3.7e-5, over n - 1 = 3
    EXPECT_NEAR(s.sd, std::sqrt(3.7e-5 / 3.0), 1e-15);
    EXPECT_DOUBLE_EQ(s.min, 0.074);
    EXPECT_DOUBLE_EQ(s.max, 0.081);
    const Spread one = spreadOf(std::vector<double>{-0.02});
    EXPECT_EQ(one.sd, 0.0);
    EXPECT_EQ(one.min, -0.02);
    EXPECT_EQ(one.max, -0.02);
    EXPECT_THROW((void)spreadOf(std::vector<double>{}), std::invalid_argument);
    EXPECT_THROW((void)spreadOf(std::vector<double>{0.1, std::nan("")}), std::invalid_argument);
}

// compareLevel interpolates the simulated series at the record's times inside [tLo, tHi].
TEST(Validation, LevelComparisonInterpolatesTheSimulationAtRecordTimes) {
    // Simulation h = 0.1 + 0.2 t, sampled every 0.01 s; record 0.02 m low at its times.
    std::vector<LevelPoint> sim;
    for (int k = 0; k <= 150; ++k)
        sim.push_back({0.01 * k, 0.1 + 0.2 * 0.01 * k});
    std::vector<LevelPoint> record;
    for (double t : {0.0, 0.2345, 0.777, 1.2, 1.5, 1.9})
        record.push_back({t, 0.1 + 0.2 * t - 0.02});
    record[2].h += 0.05; // one point 0.03 m above the simulation
    const LevelError e = compareLevel(sim, record, 0.0, 1.5);
    EXPECT_EQ(e.points, 5); // 1.9 lies outside the window
    EXPECT_NEAR(e.mean, (4 * 0.02 + 0.03) / 5.0, 1e-12);
    EXPECT_NEAR(e.max, 0.03, 1e-12);
    EXPECT_NEAR(e.meanSigned, (4 * 0.02 - 0.03) / 5.0, 1e-12);
    EXPECT_THROW(compareLevel(sim, record, 0.0, 2.0), std::invalid_argument); // 1.9 uncovered
    EXPECT_THROW(compareLevel(std::vector<LevelPoint>{{0.0, 0.1}}, record, 0.0, 1.0),
                 std::invalid_argument);
    // The shipped records: four gauges, H1 starts at the column height, the others dry.
    const auto gauges = lobovskyH300Gauges();
    ASSERT_EQ(gauges.size(), 4U);
    EXPECT_NEAR(gauges[0].series.front().h, 0.3, 1e-12);
    for (std::size_t g = 1; g < gauges.size(); ++g)
        EXPECT_EQ(gauges[g].series.front().h, 0.0) << gauges[g].name;
}

// firstTimeAbove: the first sample strictly above the level, nothing where none is.
TEST(Validation, FirstTimeAboveIsTheFirstSampleAboveTheLevel) {
    const std::vector<LevelPoint> s{{0.0, 0.1}, {0.5, 0.2}, {1.0, 0.15}, {1.5, 0.3}, {2.0, 0.4}};
    EXPECT_EQ(firstTimeAbove(s, 0.15), 0.5);
    EXPECT_EQ(firstTimeAbove(s, 0.2), 1.5); // equal is not above; a later dip does not count
    EXPECT_EQ(firstTimeAbove(s, 0.05), 0.0);
    EXPECT_FALSE(firstTimeAbove(s, 0.4).has_value());
    EXPECT_FALSE(firstTimeAbove(std::vector<LevelPoint>{}, 0.0).has_value());
}

// Issue 14's "first impact and run-up" ends where the record's water lands on the gauge nearest
// the far wall (H4): its first sample above H/2, 1.093 s; before it H4 never reaches 0.13 m, and
// the gauges further from the wall are still below H/2 (docs/validation.md 7.49).
TEST(Validation, LobovskyRunUpEndsWhereTheRecordsWaterLandsOnTheFarGauge) {
    const auto gauges = lobovskyH300Gauges();
    const double H = 0.3;
    const double end = lobovskyRunUpEnd(gauges, H);
    EXPECT_NEAR(end, 1.0933, 1e-4);
    for (const LevelPoint& p : gauges[3].series) {
        if (p.t < end) {
            EXPECT_LT(p.h, 0.13) << p.t;
        }
    }
    for (std::size_t g = 1; g < 3; ++g)
        EXPECT_GT(*firstTimeAbove(gauges[g].series, 0.5 * H), end) << gauges[g].name;
    // The far gauge is found by position, not by order; a record that never rises is an error.
    EXPECT_EQ(lobovskyFarGauge(gauges), 3U);
    std::vector<LevelGauge> reversed(gauges.rbegin(), gauges.rend());
    EXPECT_EQ(lobovskyFarGauge(reversed), 0U);
    EXPECT_EQ(lobovskyRunUpEnd(reversed, H), end);
    EXPECT_THROW((void)lobovskyRunUpEnd(gauges, 2.0), std::invalid_argument); // nothing above 1 m
    EXPECT_THROW((void)lobovskyRunUpEnd(std::span<const LevelGauge>{}, H), std::invalid_argument);
}

// The experiment against itself: H2-H4 carry the other series (ETSIN 01) on the record's own
// times, copied verbatim; the two agree through the surge and impact and part after the
// returning jet lands.
TEST(Validation, LobovskyScatterComparesTheExperimentsTwoSeries) {
    const auto gauges = lobovskyH300Gauges();
    const double H = 0.3;
    EXPECT_FALSE(lobovskyScatter(gauges[0], 0.0, 1.5).has_value()); // H1: one series only
    for (std::size_t g = 1; g < gauges.size(); ++g) {
        const LevelGauge& gauge = gauges[g];
        ASSERT_EQ(gauge.repeat.size(), gauge.series.size()) << gauge.name;
        double sum = 0.0;
        int n = 0;
        for (std::size_t k = 0; k < gauge.series.size(); ++k) {
            EXPECT_DOUBLE_EQ(gauge.repeat[k].t, gauge.series[k].t) << gauge.name << " " << k;
            if (gauge.series[k].t <= 1.5) {
                sum += std::abs(gauge.repeat[k].h - gauge.series[k].h);
                ++n;
            }
        }
        const auto whole = lobovskyScatter(gauge, 0.0, 1.5);
        ASSERT_TRUE(whole.has_value()) << gauge.name;
        EXPECT_EQ(whole->points, n) << gauge.name;
        EXPECT_NEAR(whole->mean, sum / n, 1e-12) << gauge.name;
        EXPECT_GT(whole->mean / H, 0.01) << gauge.name; // two runs, not one copied twice
        const auto early = lobovskyScatter(gauge, 0.0, 0.9);
        EXPECT_LT(early->mean / H, 0.01) << gauge.name; // the same flow up to the run-up
    }
    // Spot values of the copied files (t sqrt(g/H), h/H): H3 ETSIN 01 at 6.86207 reads
    // 0.489117, H4 at 6.25211 reads 0.737148.
    const double s = std::sqrt(9.81 / H);
    const auto at = [&](const LevelGauge& gauge, double tStar) {
        for (const LevelPoint& p : gauge.repeat)
            if (std::abs(p.t * s - tStar) < 1e-4)
                return p.h / H;
        return -1.0;
    };
    EXPECT_NEAR(at(gauges[2], 6.86207), 0.489117, 1e-9);
    EXPECT_NEAR(at(gauges[3], 6.25211), 0.737148, 1e-9);
}

// The Lobovsky scenes: the experiment's column against the upstream wall, its tank length
// (lobovsky_small.json: 1 cm longer, a whole number of 20 mm spacings), walls tall enough for the
// run-up, dt at Courant < 0.3 for the dry-bed front speed 2 sqrt(g H).
TEST(Validation, LobovskyScenesMatchTheExperimentGeometry) {
    const LobovskyGeometry geo = lobovskyH300Geometry();
    for (const char* name : {"lobovsky.json", "lobovsky_small.json"}) {
        const Scene scene = loadScene(kScenes / name);
        const Box tank = *scene.geometry.tank;
        const Box column = scene.geometry.water.at(0);
        EXPECT_DOUBLE_EQ(column.x0, tank.x0) << name;
        EXPECT_DOUBLE_EQ(column.y0, tank.y0) << name;
        EXPECT_NEAR(column.width(), geo.columnLength, 1e-12) << name;
        EXPECT_NEAR(column.height(), geo.columnHeight, 1e-12) << name;
        EXPECT_NEAR(tank.width(), geo.tankLength, 0.5 * scene.geometry.particleSpacing + 1e-9)
            << name;
        EXPECT_GE(tank.height(), geo.tankHeight) << name;
        const double front = 2.0 * std::sqrt(scene.physics.gravity * geo.columnHeight);
        EXPECT_LT(front * scene.solver.time.dt / scene.geometry.particleSpacing, 0.3) << name;
        EXPECT_DOUBLE_EQ(scene.physics.kinematicViscosity, 1e-6) << name;
        EXPECT_GE(scene.run.endTime, 1.5) << name;
    }
}

namespace {
/// The rows of a CSV text after its header, split at commas.
std::vector<std::vector<std::string>> csvRows(const std::string& text, const std::string& header) {
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, header);
    std::vector<std::vector<std::string>> rows;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::istringstream cellsIn(line);
        for (std::string c; std::getline(cellsIn, c, ',');)
            cells.push_back(c);
        rows.push_back(cells);
    }
    return rows;
}
} // namespace

TEST(Validation, RecordsCsvHoldEveryExperimentalPointAsCompared) {
    // swell-validate --records: the plots must show the very points the checks compare with.
    const auto mm = csvRows(martinMoyceRecordsCsv(), "series,T,Z");
    const auto a225 = martinMoyceA225();
    const auto a1125 = martinMoyceA1125();
    ASSERT_EQ(mm.size(), a225.size() + a1125.size());
    for (std::size_t k = 0; k < mm.size(); ++k) {
        const bool first = k < a225.size();
        const FrontPoint& p = first ? a225[k] : a1125[k - a225.size()];
        ASSERT_EQ(mm[k].size(), 3u);
        EXPECT_EQ(mm[k][0], first ? "a2.25in" : "a1.125in");
        EXPECT_DOUBLE_EQ(std::stod(mm[k][1]), p.T);
        EXPECT_DOUBLE_EQ(std::stod(mm[k][2]), p.Z);
    }
    const auto lob = csvRows(lobovskyRecordsCsv(), "gauge,series,x,t,h");
    std::size_t k = 0, repeats = 0;
    for (const LevelGauge& g : lobovskyH300Gauges()) {
        for (const auto& [name, points] :
             {std::pair{"record", g.series}, std::pair{"repeat", g.repeat}}) {
            for (const LevelPoint& p : points) {
                ASSERT_LT(k, lob.size());
                ASSERT_EQ(lob[k].size(), 5u);
                EXPECT_EQ(lob[k][0], g.name);
                EXPECT_EQ(lob[k][1], name);
                EXPECT_DOUBLE_EQ(std::stod(lob[k][2]), g.x);
                EXPECT_DOUBLE_EQ(std::stod(lob[k][3]), p.t);
                EXPECT_DOUBLE_EQ(std::stod(lob[k][4]), p.h);
                ++k;
            }
        }
        repeats += g.repeat.size();
    }
    EXPECT_EQ(k, lob.size());
    EXPECT_GT(k - repeats, 4u * 10u); // four gauges, each a record, not a stub
    EXPECT_GT(repeats, 3u * 10u);     // and H2-H4's other series
}

// Pooling the two Martin & Moyce series weights their means by their point counts.
TEST(Validation, PooledFrontErrorsWeighByPoints) {
    const FrontError a{0.1, 0.3, 0.1, 3};
    const FrontError b{0.2, 0.25, -0.2, 1};
    const FrontError p = pooled(a, b);
    EXPECT_EQ(p.points, 4);
    EXPECT_DOUBLE_EQ(p.mean, (0.3 + 0.2) / 4.0);
    EXPECT_DOUBLE_EQ(p.meanSigned, (0.3 - 0.2) / 4.0);
    EXPECT_DOUBLE_EQ(p.max, 0.3);
    EXPECT_EQ(pooled(FrontError{}, FrontError{}).mean, 0.0);
}

TEST(Validation, SurgeFrontIgnoresSplashAndWalls) {
    Particles p;
    p.add(0.1, 0.0, ParticleKind::Water);
    p.add(0.3, 0.0, ParticleKind::Water);
    p.add(0.9, 0.0, ParticleKind::Water); // splash
    p.add(2.0, 0.0, ParticleKind::Wall);
    p.n = {10.0, 8.0, 2.0, 10.0};
    EXPECT_DOUBLE_EQ(surgeFront(p, 10.0, 0.49), 0.3);
    EXPECT_DOUBLE_EQ(surgeFront(p, 10.0, 0.49, 0.1), 0.2);
}

// Martin & Moyce (1952), Phil. Trans. R. Soc. Lond. A 244, 312-324, Fig. 3 (n^2 = 2), as
// digitised in PySPH's pysph/examples/db_exp_data.py: both series (a = 1.125 in and 2.25 in)
// at their points with T = t sqrt(2g/a) in [0.8, 3.0] (9 points).
TEST(Validation, DamBreakFrontFollowsMartinMoyceAtCiResolution) {
    const Scene scene = loadScene(kScenes / "dam_break_small.json"); // a/20
    const DamBreakRun run = runDamBreak(scene, 3.05);
    ASSERT_EQ(run.outcome, kStable);
    const FrontError raw = pooled(compareFront(run.series, martinMoyceA225(), 0.8, 3.0),
                                  compareFront(run.series, martinMoyceA1125(), 0.8, 3.0));
    ASSERT_EQ(raw.points, 9);
    RecordProperty("front_error_mean", fmt::format("{:.4f}", raw.mean));
    EXPECT_LT(raw.mean, 0.35)
        << "mean |dZ| over T in [0.8, 3.0] (bound: 0.35 a, docs/validation.md)";
    // On the time origin tied to the first recorded front (alignedFront): measured 0.057 a mean,
    // 0.108 a max with the default scheme (docs/validation.md 7.11); four members jittered by
    // 1e-6 l0 agree with it to 1e-3 a at this resolution (7.13).
    const FrontError aligned = pooled(alignedFront(run.series, martinMoyceA225()).error,
                                      alignedFront(run.series, martinMoyceA1125()).error);
    ASSERT_EQ(aligned.points, 7);
    RecordProperty("aligned_front_error_mean", fmt::format("{:.4f}", aligned.mean));
    EXPECT_LT(aligned.mean, 0.06);
    EXPECT_LT(aligned.max, 0.13);
    // The front must actually travel: Z(3) well past the column (Martin & Moyce: ~3.7-4.0).
    EXPECT_GT(run.series.back().Z, 3.0);
}

// The textbook scheme stays selectable and within its own bound (measured 0.225 a at a/20;
// the default scheme's figure is in DamBreakFrontFollowsMartinMoyceAtCiResolution).
TEST(Validation, TextbookSchemeDamBreakStaysWithinItsBound) {
    Scene scene = loadScene(kScenes / "dam_break_small.json", {"solver.scheme=textbook"});
    ASSERT_EQ(scene.solver.model.gradient, GradientModel::MinimumPressure);
    const DamBreakRun run = runDamBreak(scene, 3.05);
    ASSERT_EQ(run.outcome, kStable);
    const FrontError raw = pooled(compareFront(run.series, martinMoyceA225(), 0.8, 3.0),
                                  compareFront(run.series, martinMoyceA1125(), 0.8, 3.0));
    RecordProperty("front_error_mean", fmt::format("{:.4f}", raw.mean));
    EXPECT_LT(raw.mean, 0.26);
}

// Lobovsky et al. (2014) dam break, H = 0.3 m, at CI resolution H/15 (lobovsky_small.json):
// water height at the gauges H1..H4 (the top particle, runLobovsky) after every step, compared
// with the records over t in [0, 1.5] s (compareLevel). Asserts a stable run and a worst-gauge
// error a little above the measured ones: 0.081 H (gauge H4, default scheme,
// docs/validation.md 7.11), 0.077-0.088 H over four members jittered by 1e-6 l0 (7.13); the
// textbook scheme 0.087 H. 2 threads, about 2 s.
TEST(Validation, LobovskyDamBreakRunsStableAtCiResolution) {
    const Scene scene = loadScene(kScenes / "lobovsky_small.json");
    const LobovskyRun run = runLobovsky(scene, 1.5);
    ASSERT_EQ(run.outcome, "stable");
    const auto gauges = lobovskyH300Gauges();
    ASSERT_EQ(run.top.size(), gauges.size());
    double worst = 0.0;
    for (std::size_t g = 0; g < gauges.size(); ++g) {
        const LevelError e = compareLevel(run.top[g], gauges[g].series, 0.0, 1.5);
        EXPECT_GT(e.points, 50) << gauges[g].name;
        ASSERT_TRUE(std::isfinite(e.mean)) << gauges[g].name;
        worst = std::max(worst, e.mean / run.H);
    }
    RecordProperty("mean_abs_error_over_H_worst", fmt::format("{:.4f}", worst));
    EXPECT_LT(worst, 0.105) << "worst gauge's mean |h_sim - h_exp| / H over t in [0, 1.5] s";
    // The first impact and run-up alone (until the record's water lands on H4, 1.093 s): 0.065
    // H here, 0.061-0.070 H over four jittered members, always at H4, where the simulated water
    // lands at 0.918 s, 0.175 s before the record's (0.910-0.933 s; docs/validation.md 7.49).
    // Until 0.9 s every gauge is within 0.02 H (0.0198 at most in the members).
    const double recordH = lobovskyH300Geometry().columnHeight; // the window is the record's
    const double runUpEnd = lobovskyRunUpEnd(gauges, recordH);
    double worstRunUp = 0.0, worstEarly = 0.0;
    for (std::size_t g = 0; g < gauges.size(); ++g) {
        worstRunUp = std::max(
            worstRunUp, compareLevel(run.top[g], gauges[g].series, 0.0, runUpEnd).mean / run.H);
        worstEarly =
            std::max(worstEarly, compareLevel(run.top[g], gauges[g].series, 0.0, 0.9).mean / run.H);
    }
    RecordProperty("mean_abs_error_over_H_worst_run_up", fmt::format("{:.4f}", worstRunUp));
    EXPECT_LT(worstRunUp, 0.08) << "worst gauge over the first impact and run-up";
    EXPECT_LT(worstEarly, 0.025) << "worst gauge over t in [0, 0.9] s";
    const std::optional<double> lands =
        firstTimeAbove(run.top[lobovskyFarGauge(gauges)], 0.5 * recordH);
    ASSERT_TRUE(lands.has_value()) << "the far wall's water never reached H4";
    EXPECT_LT(std::abs(*lands - runUpEnd), 0.2) << "lands on H4 at " << *lands << " s";

    // The far wall's pressure at sensor P1 against Marrone et al. (2011)'s delta-SPH at H / dx =
    // 320 (buchner2002.h, docs/validation.md 7.51), in t sqrt(g/H): here the impact at 2.763
    // (theirs 2.598), the run-up's collapse at 5.98 (theirs 6.43), mean error 0.140 rho g H;
    // four jittered members 2.754-2.772, 5.81-5.95 and 0.139-0.154.
    ASSERT_EQ(run.farWallPressure.size(), run.top[0].size());
    std::vector<PressurePoint> p1;
    const double g = scene.physics.gravity;
    for (const PressureSample& q : run.farWallPressure)
        p1.push_back({q.t * std::sqrt(g / run.H), q.p / (scene.physics.density * g * run.H)});
    const std::vector<PressurePoint> ref = buchnerP1Series(&FarWallPressureSample::deltaSph320);
    const PressureFigures sim = pressureFigures(p1);
    const PressureFigures dsph = pressureFigures(ref);
    ASSERT_TRUE(sim.impactTime && sim.peakTime) << "no impact or no collapse at P1";
    RecordProperty("p1_second_peak_time", fmt::format("{:.3f}", *sim.peakTime));
    EXPECT_LT(std::abs(*sim.impactTime - *dsph.impactTime), 0.25) << *sim.impactTime;
    EXPECT_LT(std::abs(*sim.peakTime - *dsph.peakTime), 0.75) << *sim.peakTime;
    EXPECT_LT(meanAbsPressureError(p1, ref).value(), 0.18);
}

TEST(Validation, LobovskyRunNeedsATankAndReadsTheColumnAtTheStart) {
    Scene scene = loadScene(kScenes / "lobovsky_small.json");
    // Before any step: H1 (0.3 m, inside the column) reads the column's height, H2-H4 are dry.
    const LobovskyRun start = runLobovsky(scene, 0.0);
    EXPECT_EQ(start.outcome, "stable");
    EXPECT_EQ(start.totals.steps, 0);
    ASSERT_EQ(start.top.size(), 4u);
    EXPECT_NEAR(start.top[0].at(0).h, start.H, 1e-9);
    for (std::size_t g = 1; g < 4; ++g)
        EXPECT_EQ(start.top[g].at(0).h, 0.0) << g;
    // Sensor P1 on the far wall, scaled by H = 0.3 m: 0.035-0.08 m above the floor, dry.
    EXPECT_NEAR(start.sensorLow, 0.035, 1e-12);
    EXPECT_NEAR(start.sensorHigh, 0.08, 1e-12);
    // l0 = 0.02 m: the first wall layer's particles at y = 0.05 and 0.07 m lie in the band.
    EXPECT_EQ(start.sensorParticles, 2u);
    ASSERT_EQ(start.farWallPressure.size(), 1u);
    EXPECT_EQ(start.farWallPressure[0].p, 0.0);
    scene.geometry.tank.reset(); // the gauges stand in a tank: an error naming the key
    try {
        runLobovsky(scene, 0.1);
        ADD_FAILURE() << "a scene without a tank was accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "geometry.tank");
    }
}

// The dam-break run (runDamBreak) reads the front from the column's back face and stops at the
// first step at or past the T asked for; a scene without water is an error naming the key.
TEST(Validation, DamBreakRunReadsTheColumnAtTheStartAndStopsAtItsEnd) {
    Scene scene = loadScene(kScenes / "dam_break_small.json");
    const double l0 = scene.geometry.particleSpacing;
    const DamBreakRun start = runDamBreak(scene, 0.0);
    EXPECT_EQ(start.outcome, kStable);
    EXPECT_EQ(start.totals.steps, 0);
    ASSERT_EQ(start.series.size(), 1u);
    EXPECT_EQ(start.a, scene.geometry.water.at(0).width());
    // The front particle's centre sits l0 / 2 inside the column's face.
    EXPECT_NEAR(start.series[0].Z, 1.0 - 0.5 * l0 / start.a, 1e-9);
    const DamBreakRun run = runDamBreak(scene, 0.3);
    ASSERT_EQ(run.outcome, kStable);
    ASSERT_EQ(run.series.size(), static_cast<std::size_t>(run.totals.steps) + 1);
    EXPECT_GE(run.series.back().T, 0.3);
    EXPECT_LT(run.series[run.series.size() - 2].T, 0.3);
    EXPECT_GT(run.series.back().Z, run.series.front().Z); // the column has started to collapse
    scene.geometry.water.clear();
    try {
        runDamBreak(scene, 0.3);
        ADD_FAILURE() << "a scene without water was accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "geometry.water");
    }
}

namespace {

/// The library's still-tank run (swell/bake/still_tank.h), as swell-validate still-tank takes
/// it; a run the divergence detector stops fails the test.
StillTankReport runTank(const Scene& scene, long steps, double settle) {
    StillTankReport r = runStillTank(scene, settle, steps);
    EXPECT_EQ(r.outcome, "stable");
    return r;
}

} // namespace

// Still tank, 20,000 steps at dt = 1 ms, H = 0.1 m, l0 = H/10, water's viscosity, default
// scheme: measured 0.9927 rho g H (docs/validation.md 7.11; 0.9975 before the damping against
// the shift, 7.8; without the packing factor 0.984, below; the textbook scheme reads 1.054).
// Max |u| after 2 s: 0.025 of sqrt(g H) (0.098 without the damping against the shift; the
// textbook scheme and the corrected gradient with the relaxed source keep churning at 0.5);
// the 1 % goal is not met. No water particle gets further than 0.18 l0 from where it was at
// 2 s in the next 18 s (1.71 l0 without the damping; the textbook scheme's particles wander
// 16.5 l0 in 10 s, swell-validate still-tank). The settled state is a draw (docs/validation.md
// 7.13): eight members jittered by 1e-6 l0 read bed 0.9948-0.9967, max |u| 0.023-0.036 and
// excursion 0.53-0.92 l0 (without the damping 0.074-0.148 and 0.84-2.7 l0), so the bounds
// cover those members, not only the unjittered record.
TEST(Validation, StandingWaveKeepsLinearTheorysPeriodAtCiResolution) {
    // The tank's first sloshing mode from rest (docs/validation.md 7.15), h/25, five periods.
    // Four jittered members read period -1.0 +- 0.5 %, decay 5.6 +- 1.9 % per period, first
    // amplitude 1.14 of the cosine's; the textbook scheme's surface churns and shows no wave
    // (first amplitude 0.27, period "error" -79 % from the noise's crossings).
    const Scene scene = loadScene(kScenes / "standing_wave_small.json");
    ASSERT_EQ(scene.solver.scheme, Scheme::Swell);
    const StandingWaveReport r = runStandingWave(scene);
    ASSERT_EQ(r.outcome, "stable");
    EXPECT_NEAR(r.theory.period, 1.1818, 1e-4);
    RecordProperty("period_error", fmt::format("{:.4f}", r.periodError));
    RecordProperty("decay_per_period", fmt::format("{:.4f}", r.decayPerPeriod));
    ASSERT_EQ(r.records.size(), 2u);
    for (const SloshRecord& g : r.records)
        EXPECT_GE(g.amplitudes.size(), 4u); // five periods, four whole between crossings
    EXPECT_NEAR(r.periodError, 0.0, 0.03);
    EXPECT_LT(r.decayPerPeriod, 0.12);
    EXPECT_GT(r.decayPerPeriod, -0.05);
    EXPECT_NEAR(r.firstAmplitudeOverTheory, 1.0, 0.3);
    // The two walls are half a wavelength apart: their records are in antiphase.
    EXPECT_GT(r.elevations[0].front(), 0.0);
    EXPECT_LT(r.elevations[1].front(), 0.0);

    Scene flat = scene; // no cosine top: nothing to measure, an error naming the key
    flat.geometry.waterTops.clear();
    try {
        runStandingWave(flat);
        ADD_FAILURE() << "a flat top was accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "geometry.water[0].surface");
    }
}

TEST(Validation, SolitaryWaveKeepsItsCelerityAtCiResolution) {
    // Goring's stroke for H = 0.04 m in h = 0.2 m, read at 10-30 h (docs/validation.md 7.31).
    // At h/10 four jittered members read celerity +4.7 +- 2.6 % (+0.9 to +6.7 %) against
    // sqrt(g (h + A)), the first crest 0.83-0.88 H, 20-26 % of it lost over 20 h, width +15 to
    // +21 % against Boussinesq's for its height (h/20: +3.0 +- 1.1 %, 0.94 H, 8.5 +- 2.0 %,
    // +12 +- 2 %). The bounds cover the members with a margin; a wave running 10 % off its
    // theory, or losing a third of its height, fails.
    const Scene scene = loadScene(kScenes / "solitary_wave_small.json");
    ASSERT_EQ(scene.solver.scheme, Scheme::Swell);
    const SolitaryWaveReport r = runSolitaryWave(scene);
    ASSERT_EQ(r.outcome, "stable");
    EXPECT_NEAR(r.theory.celerity, 1.5344, 1e-4);
    EXPECT_NEAR(r.stroke, 0.2066, 2e-3); // Goring: sqrt(16 H h / 3)
    const SolitaryWaveCheck& c = r.check;
    RecordProperty("celerity_error", fmt::format("{:.4f}", c.celerityError));
    RecordProperty("decay_total", fmt::format("{:.4f}", c.decayTotal));
    ASSERT_EQ(c.crests.size(), 5u);
    EXPECT_NEAR(c.celerityError, 0.0, 0.10);
    EXPECT_GT(c.firstAmplitudeOverHeight, 0.75);
    EXPECT_LT(c.firstAmplitudeOverHeight, 1.05);
    EXPECT_LT(c.decayTotal, 0.35);
    EXPECT_GT(c.decayTotal, -0.05);
    EXPECT_LT(std::abs(c.meanWidthError), 0.35);
    const double l0 = scene.geometry.particleSpacing;
    for (const SolitaryCrest& k : c.crests)
        EXPECT_LT(std::abs(k.stillLevel), 0.2 * l0) << "the gauge reads still water at x = " << k.x;

    Scene regular = scene; // not a solitary piston: an error naming the key, before any step
    regular.piston->kind = PistonKind::Sinusoidal;
    try {
        runSolitaryWave(regular);
        ADD_FAILURE() << "a sinusoidal piston was accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "piston.kind");
    }
    Scene oneGauge = scene;
    oneGauge.output.gauges.resize(1);
    try {
        runSolitaryWave(oneGauge);
        ADD_FAILURE() << "one gauge was accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "output.gauges");
    }
}

TEST(Validation, WetDamBreakFollowsStokerAtCiResolution) {
    // h0 = 0.1 m onto h1 = 0.02 m at h0/20, compared from t = 5 sqrt(h0 / g) (docs/validation.md
    // 7.43). Four jittered members read the bore's speed -2.3 +- 0.6 % (-3.0 to -1.6 %) against
    // Stoker's 0.939 m/s, the depth behind it -2.4 +- 0.2 % against his 0.0508 m and the worst
    // gauge's mean |h - h_Stoker| 3.0 +- 0.1 % of h0 (at the gate). The bounds cover them with a
    // margin; a bore 5 % off its speed, or water 5 % of h0 off the solution, fails.
    const Scene scene = loadScene(kScenes / "wet_dam_break_small.json");
    ASSERT_EQ(scene.solver.scheme, Scheme::Swell);
    const WetDamBreakReport r = runWetDamBreak(scene);
    ASSERT_EQ(r.outcome, "stable");
    EXPECT_NEAR(r.theory.boreSpeed, 0.93898, 1e-4);
    EXPECT_NEAR(r.theory.h2, 0.050787, 1e-5);
    const WetDamBreakCheck& c = r.check;
    RecordProperty("bore_speed_error", fmt::format("{:.4f}", c.boreSpeedError));
    RecordProperty("plateau_depth_error", fmt::format("{:.4f}", c.plateauDepthError));
    RecordProperty("worst_gauge", fmt::format("{:.4f}", c.meanAbsErrorOverH0Worst));
    EXPECT_GE(c.boreGauges, 5u);
    EXPECT_NEAR(c.boreSpeedError, 0.0, 0.05);
    EXPECT_NEAR(c.plateauDepthError, 0.0, 0.05);
    EXPECT_LT(c.meanAbsErrorOverH0Worst, 0.045);
    for (const WetDamBreakGauge& g : c.gauges) {
        if (!std::isnan(g.boreArrival)) { // the bore arrives when theory's does, to 0.05 s
            EXPECT_NEAR(g.boreArrival, g.boreArrivalTheory, 0.05) << "x = " << g.x;
        }
    }
}

TEST(Validation, ShoalingFollowsGrilliAtCiResolution) {
    // A solitary wave H = 0.2 h0 up a 1:34.7 beach at h0/20 against Grilli et al. (1994), the
    // clocks aligned on g0's crest (docs/validation.md 7.44). Four jittered members read the
    // incident crest -4.9 +- 1.1 %, the worst slope crest -22.7 +- 0.7 % (the crests on the
    // slope are low at every resolution), the worst gauge's mean |eta - eta_record| 0.039 +-
    // 0.006 h0, the climb from g1 to g9 -1.1 +- 1.3 % and g9's crest 1.38-1.44 times g0's; this
    // unjittered record -8.2 %, -23.8 %, 0.025 h0, +1.6 %, 1.41. The bounds cover them with a
    // margin. The textbook scheme's record (-2.4 %, -55.9 %, 0.076 h0, +8.7 %, 0.77) fails
    // three of them; a wave that does not grow up the beach fails the last.
    const Scene scene = loadScene(kScenes / "shoaling_small.json");
    ASSERT_EQ(scene.solver.scheme, Scheme::Swell);
    const ShoalingReport r = runShoaling(scene);
    ASSERT_EQ(r.outcome, "stable");
    const ShoalingCheck& c = r.check;
    RecordProperty("incident_crest_error", fmt::format("{:.4f}", c.incidentCrestError));
    RecordProperty("crest_error_worst", fmt::format("{:.4f}", c.crestErrorWorst));
    RecordProperty("worst_gauge", fmt::format("{:.4f}", c.meanAbsErrorWorst));
    RecordProperty("travel_time_error", fmt::format("{:.4f}", c.travelTimeError));
    ASSERT_EQ(c.gauges.size(), 6u);
    EXPECT_NEAR(c.incidentCrestError, 0.0, 0.12);
    EXPECT_GT(c.crestErrorWorst, -0.30);
    EXPECT_LT(c.meanAbsErrorWorst, 0.055);
    EXPECT_NEAR(c.travelTimeError, 0.0, 0.06);
    // The wave grows up the beach: g9's crest stands 1.25 times g0's or more (the record: 1.71).
    EXPECT_GT(c.gauges.back().amplification, 1.25);
    // It keeps its energy up to the break: at g1-g7 the integral of eta^2 dt over each
    // record's span reads the record's within 15 % (this record 0.97-1.04, the jittered
    // members in docs/validation.md 7.45; without particle shifting 0.93, 0.84, 0.83, 0.78,
    // the wave then keeping its shape and losing its energy). Its shape is what it lacks: its
    // front rises over about twice the record's time at g1-g5 (recorded, not bounded).
    for (std::size_t g = 1; g + 1 < c.gauges.size(); ++g) {
        const ShoalingGaugeError& e = c.gauges[g];
        RecordProperty("energy_ratio_" + e.name, fmt::format("{:.3f}", e.energyRatio));
        RecordProperty("rise_ratio_" + e.name, fmt::format("{:.3f}", e.rise / e.riseRecord));
        EXPECT_NEAR(e.energyRatio, 1.0, 0.15) << e.name;
    }
}

TEST(Validation, StillTankHydrostaticPressureWithTheDefaultScheme) {
    const Scene scene = loadScene(kScenes / "still_tank_small.json");
    ASSERT_EQ(scene.solver.scheme, Scheme::Swell);
    const StillTankReport r = runTank(scene, 20000, 2.0);
    EXPECT_EQ(r.steps, 20000);
    EXPECT_EQ(r.escaped, 0u);
    RecordProperty("bottom_pressure_ratio", fmt::format("{:.4f}", r.bottomPressureRatio));
    RecordProperty("max_speed_ratio", fmt::format("{:.4f}", r.maxSpeedOverSqrtGH));
    RecordProperty("max_excursion_l0", fmt::format("{:.3f}", r.maxExcursionOverL0));
    EXPECT_NEAR(r.bottomPressureRatio, 1.0, 0.01);
    EXPECT_LT(r.maxSpeedOverSqrtGH, 0.045);
    EXPECT_LT(r.maxExcursionOverL0, 1.2);
}

TEST(Validation, StillTankWithoutThePackingFactorShrinks) {
    // What the default's packing factor (solver.re_packing = 3.0, docs/validation.md 7.8)
    // does: without it the density term holds n at the square lattice's n0 on 2.8 l0 while
    // the water reorders towards a hexagonal packing, which reaches that n0 in 1.6 % less
    // area, so the water settles shorter and its bed pressure lower. Measured 0.9835 (the
    // default: 0.9927, above).
    Scene scene = loadScene(kScenes / "still_tank_small.json", {"solver.re_packing=0"});
    const StillTankReport r = runTank(scene, 20000, 2.0);
    EXPECT_EQ(r.escaped, 0u);
    RecordProperty("bottom_pressure_ratio", fmt::format("{:.4f}", r.bottomPressureRatio));
    EXPECT_LT(r.bottomPressureRatio, 0.99);
    EXPECT_GT(r.bottomPressureRatio, 0.97);
    EXPECT_LT(r.maxSpeedOverSqrtGH, 0.15);
}

// Time-step consistency. The default scheme gives its relaxation and shifting per step, so
// halving dt doubles both per second. With the damping against the shift the still tank at
// half its step is calm; without it the tank churns.
TEST(Validation, StillTankAtHalfTheStepIsCalmWithTheDampingAgainstTheShift) {
    const auto run = [](std::vector<std::string> overrides) {
        overrides.push_back("solver.dt=0.0005");
        const Scene scene = loadScene(kScenes / "still_tank_small.json", overrides);
        return runTank(scene, 20000, 2.0);
    };
    const StillTankReport r = run({});
    EXPECT_EQ(r.steps, 20000);
    EXPECT_EQ(r.escaped, 0u);
    RecordProperty("max_speed_ratio", fmt::format("{:.4f}", r.maxSpeedOverSqrtGH));
    RecordProperty("max_excursion_l0", fmt::format("{:.3f}", r.maxExcursionOverL0));
    RecordProperty("bed_pressure_ratio", fmt::format("{:.4f}", r.bottomPressureRatio));
    EXPECT_NEAR(r.bottomPressureRatio, 1.0, 0.015); // measured 0.9896
    EXPECT_LT(r.maxSpeedOverSqrtGH, 0.12);          // measured 0.088
    EXPECT_LT(r.maxExcursionOverL0, 1.5);           // measured 1.02 l0
    const StillTankReport undamped = run({"solver.shift_damping=false"});
    RecordProperty("undamped_max_speed_ratio", fmt::format("{:.4f}", undamped.maxSpeedOverSqrtGH));
    // Measured 0.249 and 5.2 l0; eight jittered members 0.177-0.253 and 2.4-8.0 l0, the damped
    // tank's members 0.032-0.049 and 0.10-0.44 l0.
    EXPECT_GT(undamped.maxSpeedOverSqrtGH, 0.15);
    EXPECT_GT(undamped.maxExcursionOverL0, 2.0);
}

// The lidded tank (closed_tank_small.json: no free surface): what moves there comes from the
// bulk scheme. 10,000 steps, max |u| after 5 s: measured 0.030 of sqrt(g H) with the default
// scheme (0.092 without its packing factor, whose fastest particles were those of the row
// under the lid, sliding along it; with the 2.1 l0 number-density kernel of the scheme
// before, 0.021); the first swell scheme
// (relaxed source) churned at 0.48 and the textbook scheme at 2.8 after 10 s
// (docs/validation.md sections 7.1 and 7.5).
TEST(Validation, LiddedTankBulkStaysCalmWithTheDefaultScheme) {
    const Scene scene = loadScene(kScenes / "closed_tank_small.json");
    const StillTankReport r = runTank(scene, 10000, 5.0);
    EXPECT_EQ(r.steps, 10000);
    EXPECT_EQ(r.escaped, 0u);
    RecordProperty("max_speed_ratio", fmt::format("{:.4f}", r.maxSpeedOverSqrtGH));
    EXPECT_LT(r.maxSpeedOverSqrtGH, 0.05);
}

// The goal is max |u| < 1 % of sqrt(g H) after settling. The textbook (p_j - p_i^min)
// gradient keeps the water churning at 20-50 % of sqrt(g H); the symmetric (p_i + p_j)
// gradient with gamma = 0.05 settles to about 0.5 cm/s, but surface particles whose n sits
// at beta n0 flicker between p = 0 and p > 0 and give spikes up to 1.6-1.8 % of sqrt(g H)
// (docs/validation.md section 3). Each case: 20,000 steps, about 22 s.
Scene settlingStillTank() {
    return loadScene(
        kScenes / "still_tank_small.json",
        {"solver.scheme=textbook", "solver.symmetric_gradient=true", "solver.relaxation=0.05"});
}

// Measured 0.018 of sqrt(g H) unjittered; eight members jittered by 1e-6 l0 read 0.008-0.035
// (docs/validation.md 7.13); the textbook gradient churns at 0.4-0.5.
TEST(Validation, StillTankWithSymmetricGradientSettlesBelowFivePercentOfWaveSpeed) {
    const StillTankReport r = runTank(settlingStillTank(), 20000, 10.0);
    EXPECT_EQ(r.steps, 20000);
    EXPECT_EQ(r.escaped, 0u);
    RecordProperty("bottom_pressure_ratio", fmt::format("{:.4f}", r.bottomPressureRatio));
    RecordProperty("max_speed_ratio", fmt::format("{:.4f}", r.maxSpeedOverSqrtGH));
    EXPECT_NEAR(r.bottomPressureRatio, 1.0, 0.05);
    EXPECT_LT(r.maxSpeedOverSqrtGH, 0.05);
}

// The bound: max |u| < 1 % of sqrt(g H) after settling. It holds with the paper's
// kinematic viscosity (Table 1, nu = 0.0011 m^2/s, the solver's default, which the validation
// scenes replace by water's 1e-6): the symmetric gradient with gamma = 0.05 then comes to rest
// (measured 5e-5 of sqrt(g H) after 5 s; bed pressure 1.024 rho g H). With water's viscosity
// the surface spikes above stay (0.018).
TEST(Validation, StillTankAtThePapersViscositySettlesBelowOnePercentOfWaveSpeed) {
    Scene scene = settlingStillTank();
    scene.physics.kinematicViscosity = PhysicsParams{}.kinematicViscosity; // paper Table 1
    const StillTankReport r = runTank(scene, 20000, 5.0);
    EXPECT_EQ(r.steps, 20000);
    EXPECT_EQ(r.escaped, 0u);
    RecordProperty("bottom_pressure_ratio", fmt::format("{:.4f}", r.bottomPressureRatio));
    RecordProperty("max_speed_ratio", fmt::format("{:.6f}", r.maxSpeedOverSqrtGH));
    EXPECT_NEAR(r.bottomPressureRatio, 1.0, 0.05);
    EXPECT_LT(r.maxSpeedOverSqrtGH, 0.01);
}

// Stability stress at CI resolution: dt from half to eight times the default, two spacings
// and three column aspect ratios. Every run must either finish with a finite state inside the
// domain or be stopped by the detector with a message naming step and particle. Under the
// default limits (sub-steps from Courant 0.5, the detector at 0.8) the collapse at eight times
// its step is taken in sub-steps and finishes; with sub-steps off the detector stops it.
TEST(Validation, StressSweepEitherStaysStableOrStopsWithAClearMessage) {
    const Scene base = loadScene(kScenes / "dam_break_small.json");
    struct Case {
        double dtFactor;
        double spacing;
        double aspect;
        bool substeps = true;
    };
    const std::vector<Case> cases{{0.5, 0.01, 2.0},       {2.0, 0.01, 2.0}, {1.0, 0.01, 1.0},
                                  {1.0, 0.01, 4.0},       {8.0, 0.01, 2.0}, {1.0, 0.02, 2.0},
                                  {8.0, 0.01, 2.0, false}};
    int stopped = 0;
    bool followed = false;
    for (const Case& c : cases) {
        const std::string name = fmt::format("dt_x{}_l0_{}_aspect{}{}", c.dtFactor, c.spacing,
                                             c.aspect, c.substeps ? "" : "_no_substeps");
        SCOPED_TRACE(name);
        Scene s = base;
        s.geometry.particleSpacing = c.spacing;
        s.geometry.water[0].y1 = s.geometry.water[0].y0 + c.aspect * s.geometry.water[0].width();
        s.geometry.tank->y1 = std::max(s.geometry.tank->y1, s.geometry.water[0].y1 + 0.1);
        s.solver.time.dt = base.solver.time.dt * c.dtFactor;
        if (!c.substeps)
            s.solver.time.substepCourant = 0.0;
        const DamBreakRun run = runDamBreak(s, 3.0);
        RecordProperty(name, run.outcome);
        if (run.outcome == kStable) {
            for (const FrontPoint& p : run.series)
                ASSERT_TRUE(std::isfinite(p.Z));
            EXPECT_GT(run.series.back().Z, 2.0);
            followed = followed || (c.dtFactor == 8.0 && c.substeps);
        } else {
            ++stopped;
            EXPECT_NE(run.outcome.find("step"), std::string::npos) << run.outcome;
            EXPECT_NE(run.outcome.find("particle"), std::string::npos) << run.outcome;
        }
    }
    EXPECT_TRUE(followed) << "dt x 8 is followed in sub-steps under the default limits";
    EXPECT_GE(stopped, 1) << "dt x 8 without sub-steps is far past the Courant limit and must be "
                             "stopped";
}

TEST(Validation, LineSlopeIsTheLeastSquaresSlopeAndNamesEqualX) {
    const std::vector<double> x{0.0, 1.0, 2.0, 3.0};
    const std::vector<double> y{1.0, 2.9, 5.1, 7.0};
    EXPECT_NEAR(lineSlope(x, y, "x"), 2.02, 1e-12); // 10.1 / 5
    const std::vector<double> same{1.0, 1.0};
    const std::vector<double> two{0.0, 1.0};
    try {
        lineSlope(same, two, "need distinct x");
        ADD_FAILURE() << "equal x accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "need distinct x");
    }
}

TEST(Validation, HarmonicFitRecoversAmplitudePhaseAndMean) {
    const double omega = 2.0 * std::acos(-1.0) / 0.8;
    std::vector<double> t, v;
    for (int i = 0; i < 300; ++i) {
        t.push_back(0.01 * i);
        v.push_back(0.015 * std::cos(omega * t.back() - 1.1) + 0.002 + ((i % 2) ? 1e-4 : -1e-4));
    }
    const HarmonicFit f = fitHarmonic(t, v, omega);
    EXPECT_NEAR(f.amplitude, 0.015, 2e-5);
    EXPECT_NEAR(f.phase, 1.1, 2e-3);
    EXPECT_NEAR(f.mean, 0.002, 2e-5);
    EXPECT_THROW(fitHarmonic(std::vector<double>{0.0, 1.0}, std::vector<double>{0.0, 1.0}, omega),
                 std::invalid_argument);
}

// harmonicAmplitudeStandardError (docs/validation.md 7.56) predicts how far fitHarmonic's
// amplitude moves from one noisy record of the same wave to the next. Records of a 0.77 s wave
// (amplitude 15 mm, a second harmonic of 1.5 mm) over 3 s at 0.01 s, with noise of 0.5 mm: white,
// and red with a correlation time of 0.1 s, as the deep wave's gauges read (7.56). Over 400
// records the amplitudes' standard deviation and the mean predicted standard error agree within
// 15 % for both (the prediction reads 0.95 and 0.94 of it). The red noise's density at the
// wave's frequency is 12 times its white level, so an estimator that read the residual as white
// (its variance alone) would predict 3.5 times too little there; one that did not put back the
// band the fit takes out reads a quarter low.
TEST(Validation, HarmonicAmplitudeStandardErrorPredictsTheSpreadOverNoisyRecords) {
    const double omega = 2.0 * std::numbers::pi / 0.77;
    constexpr int kRecords = 400;
    constexpr int kSamples = 300;
    double white = 0.0;
    for (double correlationTime : {0.0, 0.1}) {
        swell::test::RedNoise noise(5e-4, correlationTime, 0.01, 7);
        std::vector<double> amplitudes;
        double predicted = 0.0;
        for (int r = 0; r < kRecords; ++r) {
            const std::vector<double> e = noise.next(kSamples);
            std::vector<double> t, v;
            for (int i = 0; i < kSamples; ++i) {
                t.push_back(0.01 * i);
                v.push_back(0.015 * std::cos(omega * t.back() - 0.4) +
                            0.0015 * std::cos(2.0 * omega * t.back() - 1.0) + 0.002 + e[i]);
            }
            amplitudes.push_back(fitHarmonic(t, v, omega).amplitude);
            predicted += harmonicAmplitudeStandardError(t, v, omega) / kRecords;
        }
        const double observed = spreadOf(amplitudes).sd;
        EXPECT_NEAR(predicted / observed, 1.0, 0.15) << "correlation time " << correlationTime;
        if (correlationTime == 0.0) {
            white = predicted;
            EXPECT_NEAR(predicted, 5e-4 * std::sqrt(2.0 / kSamples), 0.1 * predicted);
        } else {
            EXPECT_GT(predicted, 2.5 * white);
        }
    }
    // Too few samples for the harmonics' fit, or samples not evenly spaced: a clear error.
    const std::vector<double> few(kStandardErrorMinSamples - 1, 0.0);
    EXPECT_THROW(harmonicAmplitudeStandardError(few, few, omega), std::invalid_argument);
    std::vector<double> t, v;
    for (int i = 0; i < 40; ++i) {
        t.push_back(i == 20 ? 0.205 : 0.01 * i);
        v.push_back(std::cos(omega * t.back()));
    }
    try {
        harmonicAmplitudeStandardError(t, v, omega);
        ADD_FAILURE() << "uneven samples accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("not evenly spaced at t = 0.205 s"), std::string::npos)
            << e.what();
    }
}

// Regular waves from a sinusoidal piston against linear wavemaker theory. The shorter
// scenes/regular_wave.json (4 m tank, three gauges from 2.5 h to 5.5 h) had its own CI run until
// 2026-12-03; it is the same wave (kh = 1.0, h/20, the same piston, water and solver), and the
// progressive wave's bounds are tighter (8 % at 2.5 h against 10 % then, 6 % since 7.39; the
// fitted wavelength 3 % against 10 %), so that run was dropped to keep CI short (docs/validation.md
// section 5). At h/15 (regular_wave_small.json) the record is too noisy for a test: the same height
// read -10 % to +16 % from one build or thread count to the next. The progressive wave over three
// wavelengths (scenes/progressive_wave.json: kh = 1.0, h/20, seven gauges from 2.5 h to 2.5 h + 3
// L; docs/validation.md 7.2), the case the 2.8 l0 kernel fixed: 15,000 water and 3,328 wall
// particles, 9,700 steps, about 3 min with 2 threads. Each gauge's height is fitted over its own
// window, from the grown wave's arrival to the end of the run (7.39): six periods at 2.5 h, two at
// the farthest gauge. The height lost over 3 L is read along the least-squares line of ln H
// through all gauges (7.40), and as the ratio of the last to the first. Measured with numerics
// 5 (any thread count gives the same bits): height at 2.5 h -1.1 %, every gauge within 4.4 %,
// lost over 3 L 4.2 % along the line (3.4 % as the ratio), wavelength +0.7 %. The record is
// sensitive to round-off, which the flow amplifies, and another CPU's libm (its last bits) may
// move it: sixteen members jittered by 1e-6 l0 (seeds 1-16) read -1.4 +- 2.0 % at 2.5 h (-5.1
// to +2.4 %), worst gauge 1.9 to 7.4 %, lost over 3 L -3.5 to 8.1 % along the line (-3.1 to
// 7.5 % as the ratio), wavelength +0.7 to +1.8 %. The bounds cover that spread; the 2.1 l0
// kernel lost 14.2 % over 3 L and the textbook scheme 83 %, so a regression to either fails.
TEST(Validation, ProgressiveWaveKeepsItsHeightOverThreeWavelengthsAtCiResolution) {
    const RegularWaveCheck c = bakeRegularWave("progressive_wave.json");
    ASSERT_EQ(c.heights.size(), 7u);
    EXPECT_NEAR(c.heightError(0), 0.0, 0.06) << "H at 2.5 h = " << c.heights[0] << " m";
    for (std::size_t g = 0; g < c.heights.size(); ++g) {
        EXPECT_NEAR(c.heightError(g), 0.0, 0.10) << "gauge at x = " << c.gauges[g] << " m";
    }
    EXPECT_LT(c.decayOverSpan, 0.10) << "lost over 3 L along the line through all gauges";
    EXPECT_LT(c.decayTotal, 0.10) << "1 - H(last gauge) / H(first gauge)";
    EXPECT_NEAR(c.wavelengthFitError(), 0.0, 0.03)
        << "L = " << c.wavelengthFit << " m, theory " << c.theory.wavelength;
    // One record's standard errors from its own fluctuations (docs/validation.md 7.56): this
    // record reads 1.0-2.2 % of H per gauge and 1.6 % for the loss, and eight jittered members'
    // spread 1.2-2.0 % and 2.5 %, which one record's figures predict. A NaN, a zero or an
    // estimate off by more than a factor of two fails.
    for (std::size_t g = 0; g < c.heights.size(); ++g) {
        EXPECT_GT(c.heightStandardErrors[g], 0.005 * c.theory.height) << c.gauges[g];
        EXPECT_LT(c.heightStandardErrors[g], 0.04 * c.theory.height) << c.gauges[g];
    }
    EXPECT_GT(c.decayOverSpanStandardError, 0.005);
    EXPECT_LT(c.decayOverSpanStandardError, 0.04);
}
