// The bake driver on the small surging scene: cache contents and metadata, determinism,
// cancellation and divergence leave nothing at the output path, scene errors of a bake,
// checkpoints and a resume that gives the uninterrupted bake's cache byte for byte.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include "swell/bake/bake_driver.h"
#include "swell/bake/checkpoint.h"
#include "swell/bake/classification.h"
#include "swell/bake/error.h"
#include "swell/bake/numerics_version.h"
#include "swell/cache/reader.h"
#include "temp_dir.h"

using namespace swell::bake;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const fs::path kScenes = SWELL_SCENES_DIR;

class BakeDriver : public ::testing::Test {
protected:
    void SetUp() override { m_dir = m_tmp.path(); }

    /// A shipped scene shortened to `endTime` seconds.
    static Scene shortened(const char* file, double endTime) {
        return loadScene(kScenes / file, {fmt::format("solver.end_time={}", endTime)});
    }
    static Scene smallSurging(double endTime) { return shortened("surging_small.json", endTime); }
    static std::string bytes(const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    /// Files in the test directory (a cancelled bake must leave no temporary behind).
    std::size_t filesInDir() const {
        return static_cast<std::size_t>(
            std::distance(fs::directory_iterator(m_dir), fs::directory_iterator()));
    }
    /// Bakes `scene` with checkpoints every `every` steps and "crashes" (an exception out of
    /// the progress callback, so no checkpoint is written at that step) after step `crashAt`.
    void crashingBake(const Scene& scene, const BakeOptions& base, long every, long crashAt) const {
        struct Crash {};
        BakeOptions opt = base;
        opt.checkpointEvery = every;
        opt.onProgress = [&](const BakeProgress& p) {
            if (p.step == crashAt)
                throw Crash{};
        };
        EXPECT_THROW(runBake(scene, opt), Crash);
        EXPECT_FALSE(fs::exists(opt.output));
        ASSERT_TRUE(fs::exists(checkpointPath(opt.output)));
    }
    /// The CheckpointError message of resuming `opt.output`'s bake ("" if it completes).
    static std::string resumeError(const Scene& scene, BakeOptions opt) {
        opt.resume = true;
        try {
            runBake(scene, opt);
        } catch (const CheckpointError& e) {
            return e.what();
        }
        return "";
    }
    swell::test::TempDir m_tmp{"swell_bake_driver_"};
    fs::path m_dir;
};

} // namespace

TEST_F(BakeDriver, SmallSurgingBakeWritesAVerifiableCacheThatDescribesItself) {
    const Scene scene = smallSurging(1.0);
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    opt.probes = m_dir / "s.csv";
    opt.sceneFile = "surging_small.json";
    opt.overrides = {"solver.end_time=1.0"};
    opt.programVersion = "test";
    long lastStep = 0;
    opt.onProgress = [&](const BakeProgress& p) {
        EXPECT_EQ(p.step, lastStep + 1);
        lastStep = p.step;
    };
    const BakeSummary s = runBake(scene, opt);
    EXPECT_EQ(lastStep, 500);
    EXPECT_EQ(s.steps, 500);
    EXPECT_EQ(s.frameIntervalSteps, 10);
    EXPECT_EQ(s.frames, 51u); // frame 0 (initial state) + one per 10 steps
    EXPECT_EQ(s.particlesWater, 800u);
    EXPECT_GT(s.surfaceMean, 50.0);
    EXPECT_LT(s.surfaceMean + s.splashMean, 0.5 * 800.0); // deep particles are not stored
    EXPECT_NEAR(s.reduction, 800.0 / (s.surfaceMean + s.splashMean), 1e-9);
    EXPECT_EQ(s.cacheBytes, fs::file_size(opt.output));

    const swell::cache::Reader r(opt.output); // validates header and index
    EXPECT_EQ(r.frameCount(), 51u);
    EXPECT_EQ(r.header().seed, 7u);
    EXPECT_EQ(r.header().frameInterval, 10u);
    EXPECT_DOUBLE_EQ(r.header().dt, 0.002);
    EXPECT_LE(r.header().domain.xMin, -0.04f); // covers the tank and its walls
    EXPECT_GE(r.header().domain.xMax, 2.04f);
    const json meta = json::parse(r.header().metadataJson);
    EXPECT_EQ(meta["program"], "swell-bake");
    EXPECT_EQ(meta["scene_file"], "surging_small.json");
    EXPECT_EQ(meta["overrides"][0], "solver.end_time=1.0");
    EXPECT_EQ(meta["seed"], 7);
    EXPECT_EQ(meta["frame_interval_steps"], 10);
    // Every resolved parameter: the stored scene parses back to the same scene.
    EXPECT_EQ(toJson(parseScene(meta["scene"])), toJson(scene));
    EXPECT_EQ(meta["scene"]["solver"]["ppe_tolerance"], scene.solver.pressure.tolerance);
    // Replay block (replay_window.h): the 2 m tank, still water 0.16 m, l0 = 20 mm; random piston
    // (never behind x0): ramp 0.5 s + 2 m at c_g(T = 0.8 s, h = 0.16 m) = 0.7492 m/s = 3.169 s.
    // It describes the scene, not this shortened run.
    const json& replay = meta["replay"];
    ASSERT_TRUE(replay.is_object()) << meta.dump();
    EXPECT_EQ(replay.size(), 6u) << replay.dump();
    EXPECT_DOUBLE_EQ(replay["water_x_min"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(replay["water_x_max"].get<double>(), 2.0);
    EXPECT_DOUBLE_EQ(replay["still_water_level"].get<double>(), 0.16);
    EXPECT_DOUBLE_EQ(replay["still_water_level"].get<double>(),
                     meta["still_water_level"].get<double>());
    EXPECT_DOUBLE_EQ(replay["particle_spacing"].get<double>(), 0.02);
    EXPECT_NEAR(replay["steady_start_s"].get<double>(), 3.1694, 1e-3);
    EXPECT_NE(replay["steady_reason"].get<std::string>().find("= 3.17 s"), std::string::npos)
        << replay.dump();
    EXPECT_EQ(toJson(s)["replay"], replay); // the --json summary shows the same block

    std::size_t surface = 0;
    for (std::size_t f = 0; f < r.frameCount(); ++f) {
        const swell::cache::Frame fr = r.readFrame(f);
        surface += fr.surfaceCount();
        for (std::size_t k = 2; k < fr.surface.size(); k += 2)
            ASSERT_LE(fr.surface[k - 2], fr.surface[k]); // by x
    }
    EXPECT_NEAR(static_cast<double>(surface) / 51.0, s.surfaceMean, 1e-9);

    std::ifstream csv(opt.probes);
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "time,front_x,gauge_0.5,gauge_1,gauge_1.5");
    int rows = 0;
    while (std::getline(csv, line))
        ++rows;
    EXPECT_EQ(rows, 51); // one per stored frame
    EXPECT_EQ(filesInDir(), 2u);
}

TEST_F(BakeDriver, SameSceneSeedAndThreadsGiveAByteIdenticalCache) {
    const Scene scene = smallSurging(0.4);
    BakeOptions a;
    a.output = m_dir / "a.swell";
    runBake(scene, a);
    BakeOptions b = a;
    b.output = m_dir / "b.swell";
    runBake(scene, b);
    EXPECT_EQ(bytes(a.output), bytes(b.output));
    // A different seed gives other piston cycles, hence another cache.
    json j = toJson(scene);
    j["seed"] = 8;
    BakeOptions c = a;
    c.output = m_dir / "c.swell";
    runBake(parseScene(j), c);
    EXPECT_NE(bytes(a.output), bytes(c.output));
}

TEST_F(BakeDriver, CancelledBakeLeavesNothing) {
    const Scene scene = smallSurging(1.0);
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    opt.probes = m_dir / "s.csv";
    long steps = 0;
    opt.onProgress = [&](const BakeProgress& p) { steps = p.step; };
    opt.cancelled = [&] { return steps >= 37; };
    EXPECT_THROW(runBake(scene, opt), BakeCancelled);
    EXPECT_EQ(steps, 37);
    EXPECT_EQ(filesInDir(), 0u) << "no cache, no probes, no temporary file";
}

TEST_F(BakeDriver, DivergingBakeNamesStepTimeParticleAndLeavesNoCache) {
    json j = toJson(smallSurging(1.0));
    j["solver"]["ppe_max_iterations"] = 1; // the pressure solve cannot converge
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    try {
        runBake(parseScene(j), opt);
        FAIL() << "expected DivergenceError";
    } catch (const DivergenceError& e) {
        EXPECT_EQ(e.step(), 1);
        EXPECT_NE(std::string(e.what()).find("did not converge"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("particle"), std::string::npos);
    }
    EXPECT_EQ(filesInDir(), 0u);
}

// Every shipped scene passes the bake's own checks (frames a whole number of steps apart, a
// step count in range), not only the loader's: a scene that stores a frame every 0.01 s at
// dt = 0.8 ms loads, and swell-validate runs it, but swell-bake refuses it.
TEST(BakeDriverScenes, EveryShippedSceneIsBakeable) {
    int scenes = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(kScenes)) {
        if (e.path().extension() != ".json")
            continue;
        SCOPED_TRACE(e.path().filename().string());
        const Scene s = loadScene(e.path());
        EXPECT_NO_THROW((void)frameIntervalSteps(s));
        EXPECT_NO_THROW((void)totalSteps(s));
        ++scenes;
    }
    EXPECT_GE(scenes, 19);
}

TEST_F(BakeDriver, SceneErrorsOfABake) {
    json j = toJson(smallSurging(1.0));
    j["output"]["frame_interval"] = 0.003; // 1.5 steps of 2 ms
    try {
        frameIntervalSteps(parseScene(j));
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "output.frame_interval");
    }
    // Whole numbers of steps beyond the header's 32 bits, and far beyond a double's integers:
    // refused naming the key, not wrapped to "every 1 steps".
    for (const double interval : {2147483.6485 * 2.0, 4294967.296 * 2.0, 1e300}) {
        j["output"]["frame_interval"] = interval;
        try {
            frameIntervalSteps(parseScene(j));
            FAIL() << interval;
        } catch (const SceneError& e) {
            EXPECT_EQ(e.key(), "output.frame_interval");
            EXPECT_NE(std::string(e.what()).find("at most 1e9 steps"), std::string::npos)
                << e.what();
        }
    }
    j = toJson(smallSurging(1.0));
    j["solver"]["adaptive_dt"] = true;
    try {
        frameIntervalSteps(parseScene(j));
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "solver.adaptive_dt");
    }
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    EXPECT_THROW(runBake(parseScene(j), opt), SceneError);
    EXPECT_EQ(filesInDir(), 0u);
    // Water placed outside the tank would read as water gone over its wall: refused up front.
    j = toJson(smallSurging(1.0));
    j["geometry"]["water"].push_back({{"x0", 2.2}, {"y0", 0.0}, {"x1", 2.3}, {"y1", 0.1}});
    try {
        runBake(parseScene(j), opt);
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "geometry.water[1]");
        EXPECT_NE(std::string(e.what()).find("starts outside the tank"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(filesInDir(), 0u);
}

TEST(BakeWarnings, SteepPistonWaveIsReported) {
    json j = json::parse(R"({
        "geometry": {"particle_spacing": 0.02, "tank": {"x0": 0, "y0": 0, "x1": 2.0, "y1": 0.4},
                     "water": [{"x0": 0, "y0": 0, "x1": 2.0, "y1": 0.2}]},
        "piston": {"kind": "sinusoidal", "period": 1.0, "stroke": 0.02},
        "solver": {"dt": 0.002}
    })");
    EXPECT_TRUE(sceneWarnings(parseScene(j)).empty()); // H/L about 0.015
    j["piston"]["stroke"] = 0.3;                       // H/L about 0.2: beyond Miche's 0.12
    const auto w = sceneWarnings(parseScene(j));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("Miche"), std::string::npos);
}

// Paper Sec. 3.3.2: the ripple channel recycles water from the outflow to the inflow and
// keeps the particle count.
TEST_F(BakeDriver, RippleChannelRecyclesWaterAndConservesTheCount) {
    const Scene scene = shortened("ripple_small.json", 1.0);
    BakeOptions opt;
    opt.output = m_dir / "r.swell";
    const BakeSummary s = runBake(scene, opt);
    EXPECT_GT(s.recycled, 20u);
    const swell::cache::Reader r(opt.output);
    EXPECT_EQ(r.frameCount(), 51u);
    MpsSolver initial = makeSolver(scene);
    EXPECT_EQ(s.particlesWater, initial.particles().count(ParticleKind::Water));
    // Stored particles never exceed the water count, and the last frame still has a surface.
    const swell::cache::Frame last = r.readFrame(50);
    EXPECT_GT(last.surfaceCount(), 30u);
    EXPECT_LE(last.surfaceCount() + last.splashCount(), s.particlesWater);
}

// A bake resumed from a checkpoint gives the uninterrupted bake's cache and probes
// byte for byte, and the checkpoint is gone once the cache is complete.
TEST_F(BakeDriver, ResumedBakeIsByteIdenticalToAnUninterruptedOne) {
    const Scene scene = smallSurging(1.0);
    BakeOptions ref;
    ref.output = m_dir / "ref.swell";
    ref.probes = m_dir / "ref.csv";
    ref.sceneFile = "surging_small.json";
    ref.programVersion = "test";
    const BakeSummary whole = runBake(scene, ref);

    BakeOptions opt = ref;
    opt.output = m_dir / "s.swell";
    opt.probes = m_dir / "s.csv";
    crashingBake(scene, opt, 60, 200); // last checkpoint: step 180 (between two stored frames)
    EXPECT_EQ(readCheckpoint(checkpointPath(opt.output)).solver.step, 180);
    // What a SIGKILLed run leaves (no process has pid 999999999): removed by the resume.
    std::ofstream(m_dir / "s.swell.tmp-999999999") << "partial cache";
    std::ofstream(m_dir / "s.swell.ckpt.tmp-999999999") << "partial checkpoint";
    std::ofstream(m_dir / "s.swell.tmp-notapid") << "not ours";
    opt.resume = true;
    long first = -1, last = 0;
    opt.onProgress = [&](const BakeProgress& p) {
        if (first < 0)
            first = p.step;
        EXPECT_EQ(p.firstStep, 180);
        last = p.step;
    };
    const BakeSummary resumed = runBake(scene, opt);
    EXPECT_EQ(first, 181);
    EXPECT_EQ(last, 500);
    EXPECT_EQ(resumed.resumedFromStep, 180);
    EXPECT_EQ(bytes(opt.output), bytes(ref.output));
    EXPECT_EQ(bytes(opt.probes), bytes(ref.probes));
    EXPECT_EQ(resumed.frames, whole.frames);
    EXPECT_EQ(resumed.surfaceMean, whole.surfaceMean);
    EXPECT_EQ(resumed.keptMax, whole.keptMax);
    EXPECT_EQ(resumed.maxCourant, whole.maxCourant);
    // Conservation figures: the start is the scene's initial state in both runs.
    EXPECT_EQ(resumed.start.potentialEnergy, whole.start.potentialEnergy);
    EXPECT_EQ(resumed.start.volume, whole.start.volume);
    EXPECT_EQ(resumed.end.kineticEnergy, whole.end.kineticEnergy);
    EXPECT_GT(resumed.checkpoints, 0u); // the resumed run keeps the checkpoint interval
    EXPECT_FALSE(fs::exists(checkpointPath(opt.output))) << "removed after a successful bake";
    EXPECT_FALSE(fs::exists(m_dir / "s.swell.tmp-999999999"));
    EXPECT_FALSE(fs::exists(m_dir / "s.swell.ckpt.tmp-999999999"));
    EXPECT_TRUE(fs::exists(m_dir / "s.swell.tmp-notapid"));
    EXPECT_EQ(filesInDir(), 5u); // the two caches, the two probe files and "notapid"
}

TEST_F(BakeDriver, ResumedRippleBakeWithRecyclingIsByteIdentical) {
    const Scene scene = shortened("ripple_small.json", 0.8);
    BakeOptions ref;
    ref.output = m_dir / "ref.swell";
    const BakeSummary whole = runBake(scene, ref);
    BakeOptions opt = ref;
    opt.output = m_dir / "r.swell";
    crashingBake(scene, opt, 70, 300);
    const BakeSummary resumed = runBake(scene, [&] {
        BakeOptions o = opt;
        o.resume = true;
        return o;
    }());
    EXPECT_EQ(bytes(opt.output), bytes(ref.output));
    EXPECT_EQ(resumed.recycled, whole.recycled); // the counter continues from the checkpoint
}

TEST_F(BakeDriver, CancelledBakeWithCheckpointsSavesOneAndResumes) {
    const Scene scene = smallSurging(0.6);
    BakeOptions ref;
    ref.output = m_dir / "ref.swell";
    runBake(scene, ref);
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    opt.checkpointEvery = 1000; // none due before the stop: the cancel writes it
    long steps = 0;
    opt.onProgress = [&](const BakeProgress& p) { steps = p.step; };
    opt.cancelled = [&] { return steps >= 77; };
    try {
        runBake(scene, opt);
        FAIL() << "expected BakeCancelled";
    } catch (const BakeCancelled& e) {
        EXPECT_NE(std::string(e.what()).find("--resume"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(opt.output));
    EXPECT_EQ(readCheckpoint(checkpointPath(opt.output)).solver.step, 77);
    BakeOptions again;
    again.output = opt.output;
    again.resume = true;
    again.checkpointEvery = 25; // another interval changes nothing in the cache
    runBake(scene, again);
    EXPECT_EQ(bytes(opt.output), bytes(ref.output));
    EXPECT_FALSE(fs::exists(checkpointPath(opt.output)));
}

// Resume across an upgrade: a checkpoint written by one build (program version "1.0") is resumed by
// another ("2.0") with another thread count (the scene is below 4096 particles, so threads do not
// change its numbers); the cache equals the new build's uninterrupted bake byte for byte.
TEST_F(BakeDriver, ResumeWorksAcrossARebuildWithTheSameNumerics) {
    const Scene scene = smallSurging(0.6);
    BakeOptions old;
    old.output = m_dir / "s.swell";
    old.programVersion = "1.0";
    old.threads = 1;
    crashingBake(scene, old, 50, 120);
    BakeOptions now = old;
    now.programVersion = "2.0";
    now.threads = 2;
    now.resume = true;
    const BakeSummary resumed = runBake(scene, now);
    EXPECT_EQ(resumed.resumedFromStep, 100);
    BakeOptions whole = now;
    whole.resume = false;
    whole.output = m_dir / "whole.swell";
    runBake(scene, whole);
    EXPECT_EQ(bytes(now.output), bytes(whole.output));
    const swell::cache::Reader r(now.output);
    EXPECT_EQ(json::parse(r.header().metadataJson).at("numerics_version"), kNumericsVersion);
}

// The thread count never changes the numbers (numerics_version.h): a scene large enough for
// the pressure solve's matrix-vector product to run in parallel gives the same cache byte for
// byte with 1, 2 and 3 threads (3 splits the rows unevenly), and a checkpoint written with one
// thread count is resumed with another. (The driver does not set the OpenMP thread count; the
// program does, so the test sets it too.)
TEST_F(BakeDriver, LargeSceneGivesTheSameCacheWithAnyThreadCount) {
    const Scene scene = loadScene(kScenes / "surging_small.json",
                                  {"solver.end_time=0.05", "geometry.particle_spacing=0.005",
                                   "solver.dt=0.0005", "output.frame_interval=0.005"});
    // 12,800 water particles: the pressure solve has well over the 4096 rows from which its
    // matrix-vector product runs in parallel (parallel_thresholds.h).
    ASSERT_GE(makeSolver(scene).particles().size(), 3 * std::size_t{4096});
    const int before = omp_get_max_threads();
    const auto bake = [&](BakeOptions opt) {
        omp_set_num_threads(opt.threads);
        const BakeSummary s = runBake(scene, opt);
        omp_set_num_threads(before);
        return s;
    };
    BakeOptions one;
    one.output = m_dir / "one.swell";
    one.threads = 1;
    bake(one);
    for (const int threads : {2, 3}) {
        BakeOptions many = one;
        many.output = m_dir / fmt::format("t{}.swell", threads);
        many.threads = threads;
        bake(many);
        EXPECT_EQ(bytes(many.output), bytes(one.output)) << threads << " threads";
    }
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    opt.threads = 1;
    omp_set_num_threads(1);
    crashingBake(scene, opt, 40, 60);
    omp_set_num_threads(before);
    BakeOptions other = opt;
    other.threads = 2;
    other.resume = true;
    EXPECT_EQ(bake(other).resumedFromStep, 40);
    EXPECT_EQ(bytes(other.output), bytes(one.output));
}

// Sub-steps (solver.substep_courant) survive a resume: the speed that decides the next
// step's split is part of the checkpoint, so a bake whose steps are split resumes to the same
// cache byte for byte and counts the same sub-steps. (substep_courant 0.05: steps split from
// 0.4 m/s, which the piston's first waves reach.)
TEST_F(BakeDriver, ResumeOfABakeWithSubstepsMatchesTheWholeBake) {
    const Scene scene =
        loadScene(kScenes / "surging_small.json",
                  {"solver.end_time=2.0", "solver.dt=0.0025", "solver.substep_courant=0.05"});
    BakeOptions opt;
    opt.output = m_dir / "whole.swell";
    const BakeSummary whole = runBake(scene, opt);
    ASSERT_GT(whole.splitSteps, 0u) << "the scene must split steps";
    EXPECT_GT(whole.substeps, 2 * whole.splitSteps - 1);
    EXPECT_LE(whole.maxCourant, 0.5);
    opt.output = m_dir / "s.swell";
    crashingBake(scene, opt, 200, 500);
    opt.resume = true;
    const BakeSummary resumed = runBake(scene, opt);
    EXPECT_EQ(resumed.resumedFromStep, 400);
    EXPECT_EQ(bytes(opt.output), bytes(m_dir / "whole.swell"));
    EXPECT_EQ(resumed.splitSteps, whole.splitSteps);
    EXPECT_EQ(resumed.substeps, whole.substeps);
}

// Every bake (not only a resume) first removes what killed bakes of the same output left:
// temporaries of the cache, checkpoint and probes of processes that are gone, never those of
// a live process (pid 1) or files that only look alike.
TEST_F(BakeDriver, BakeRemovesStaleTemporariesOfDeadProcessesOnly) {
    for (const char* f :
         {"s.swell.tmp-999999999", "s.swell.ckpt.tmp-999999999", "s.csv.tmp-999999999",
          "s.swell.tmp-1", "s.swell.tmp-99x", "other.swell.tmp-999999999"})
        std::ofstream(m_dir / f) << "left behind";
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    opt.probes = m_dir / "s.csv";
    runBake(smallSurging(0.1), opt);
    for (const char* gone :
         {"s.swell.tmp-999999999", "s.swell.ckpt.tmp-999999999", "s.csv.tmp-999999999"})
        EXPECT_FALSE(fs::exists(m_dir / gone)) << gone;
    for (const char* kept : {"s.swell.tmp-1", "s.swell.tmp-99x", "other.swell.tmp-999999999"})
        EXPECT_TRUE(fs::exists(m_dir / kept)) << kept;
    EXPECT_FALSE(fs::exists(m_dir / "s.swell.lock")) << "the lock file goes with the lock";
}

TEST_F(BakeDriver, ResumeIsRefusedWithoutACheckpointOrForADifferentBake) {
    const Scene scene = smallSurging(0.6);
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    opt.threads = 1;
    const fs::path ckpt = checkpointPath(opt.output);
    std::string e = resumeError(scene, opt);
    EXPECT_EQ(e.rfind(ckpt.string() + ": no checkpoint", 0), 0u) << e;
    EXPECT_EQ(filesInDir(), 0u);

    crashingBake(scene, opt, 50, 120);
    json j = toJson(scene);
    j["physics"]["kinematic_viscosity"] = 1e-6;
    e = resumeError(parseScene(j), opt);
    EXPECT_NE(e.find("different bake"), std::string::npos) << e;
    EXPECT_NE(e.find("/scene/physics/kinematic_viscosity"), std::string::npos) << e;
    BakeOptions overrides = opt;
    overrides.overrides = {"solver.end_time=0.6"};
    EXPECT_NE(resumeError(scene, overrides).find("/overrides"), std::string::npos);
    // Refused resumes leave the checkpoint for a correct one and no cache.
    EXPECT_FALSE(fs::exists(opt.output));
    EXPECT_EQ(resumeError(scene, opt), "");
    EXPECT_TRUE(fs::exists(opt.output));
}

TEST_F(BakeDriver, DamagedCheckpointIsRefusedNamingTheFile) {
    const Scene scene = smallSurging(0.6);
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    crashingBake(scene, opt, 50, 120);
    const fs::path ckpt = checkpointPath(opt.output);
    fs::resize_file(ckpt, fs::file_size(ckpt) - 100);
    const std::string e = resumeError(scene, opt);
    EXPECT_EQ(e.rfind(ckpt.string() + ": damaged checkpoint", 0), 0u) << e;
    EXPECT_FALSE(fs::exists(opt.output));
}

// The summary reports conservation figures. A still tank keeps its water, its
// volume (from the mean number density) and, starting at rest, its energy can only drop
// (viscosity, collisions) or grow by the solver's own error: both stay small in a short run.
TEST_F(BakeDriver, SummaryReportsConservationOfCountVolumeAndEnergy) {
    const Scene scene = shortened("still_tank_small.json", 0.5);
    BakeOptions opt;
    opt.output = m_dir / "still.swell";
    const BakeSummary s = runBake(scene, opt);
    EXPECT_EQ(s.start.water, 200u);
    EXPECT_EQ(s.end.water, 200u);
    EXPECT_EQ(s.end.inTank, 200u);
    // At rest on the lattice: 200 particles of l0^2 = 1e-4 m^2, i.e. the 0.2 m x 0.1 m water.
    EXPECT_NEAR(s.start.volume, 0.02, 0.02 * 0.02);
    EXPECT_NEAR(s.end.volume / s.start.volume, 1.0, 0.03);
    EXPECT_DOUBLE_EQ(s.start.kineticEnergy, 0.0);
    // Potential energy of the column above the bed: rho g W H^2 / 2 = 1000 9.81 0.2 0.01 / 2.
    EXPECT_NEAR(s.start.potentialEnergy, 9.81, 0.01);
    const json sj = toJson(s);
    ASSERT_TRUE(sj.contains("conservation"));
    EXPECT_EQ(sj["conservation"]["water_lost"], 0);
    EXPECT_LT(std::abs(sj["conservation"]["energy_drift"].get<double>()), 0.02);
    EXPECT_LT(std::abs(sj["conservation"]["volume_change"].get<double>()), 0.03);
}

// The demo's surging scene breaks (paper Sec. 3.3.1: "breaking, merging and collision"): the
// default scheme's bake keeps splash particles in its frames (measured 1.39 per frame with
// numerics 5, against 0.24 for a version of the scene whose waves did not break) and no water
// leaves the tank.
TEST_F(BakeDriver, SurgingSmallBreaksWithSplashesAndKeepsItsWater) {
    const Scene scene = loadScene(kScenes / "surging_small.json");
    BakeOptions opt;
    opt.output = m_dir / "surging.swell";
    const BakeSummary sum = runBake(scene, opt);
    RecordProperty("splash_mean", fmt::format("{:.3f}", sum.splashMean));
    EXPECT_GT(sum.splashMean, 1.2);
    EXPECT_EQ(sum.end.inTank, sum.particlesWater);
    // The surface layer (distribution test): about one particle per l0 along the 2 m tank.
    EXPECT_GT(sum.surfaceMean, 0.9 * 2.0 / scene.geometry.particleSpacing);
}

namespace {
/// A column of water twice as tall as the tank's walls, against the front wall: its top half
/// has nothing on its right and falls over the wall (spill.h). The domain leaves room for the
/// run-up at the back wall (0.5 m) and for water falling outside the tank.
Scene overfullTank(double endTime) {
    json j = toJson(loadScene(kScenes / "dam_break_small.json"));
    j["name"] = "overfull";
    j["geometry"]["tank"] = {{"x0", 0.0}, {"y0", 0.0}, {"x1", 0.3}, {"y1", 0.1}};
    j["geometry"]["water"] = json::array({{{"x0", 0.2}, {"y0", 0.0}, {"x1", 0.3}, {"y1", 0.2}}});
    j["geometry"]["domain"] = {{"x0", -0.2}, {"y0", -0.2}, {"x1", 0.6}, {"y1", 1.0}};
    j["solver"]["end_time"] = endTime;
    return parseScene(j);
}
} // namespace

TEST_F(BakeDriver, WaterOverTheWallLeavesTheRunAndIsCounted) {
    const Scene scene = overfullTank(0.4);
    BakeOptions opt;
    opt.output = m_dir / "overfull.swell";
    const BakeSummary s = runBake(scene, opt);
    RecordProperty("spilled", static_cast<int>(s.spilled));
    EXPECT_GT(s.spilled, 20u);
    EXPECT_LT(s.spilled, s.particlesWater / 2);
    EXPECT_EQ(s.end.water + s.spilled, s.particlesWater);
    const json sj = toJson(s);
    EXPECT_EQ(sj["conservation"]["water_lost"], s.spilled);
    EXPECT_EQ(sj["spilled"], s.spilled);
    ASSERT_FALSE(s.warnings.empty());
    EXPECT_NE(s.warnings.back().find("went over the tank's walls"), std::string::npos)
        << s.warnings.back();
    // The stored frames never hold water beyond the front wall's outer face (0.3 m + 4 layers).
    swell::cache::Reader r(opt.output);
    for (std::size_t f = 0; f < r.frameCount(); ++f) {
        const swell::cache::Frame fr = r.readFrame(f);
        for (std::size_t k = 0; k < fr.surface.size(); k += 2)
            ASSERT_LE(fr.surface[k], 0.3 + 4 * 0.005 + 1e-6) << "frame " << f;
        for (std::size_t k = 0; k < fr.splash.size(); k += 4)
            ASSERT_LE(fr.splash[k], 0.3 + 4 * 0.005 + 1e-6) << "frame " << f;
    }
}

TEST_F(BakeDriver, ResumeAfterWaterWentOverTheWallIsByteIdentical) {
    const Scene scene = overfullTank(0.4);
    BakeOptions ref;
    ref.output = m_dir / "ref.swell";
    const BakeSummary whole = runBake(scene, ref);
    BakeOptions opt;
    opt.output = m_dir / "s.swell";
    crashingBake(scene, opt, 500, 650); // checkpoint at step 500, t = 0.25 s
    const Checkpoint ck = readCheckpoint(checkpointPath(opt.output));
    ASSERT_FALSE(ck.solver.removedWater.empty()) << "water has gone by the checkpoint";
    ASSERT_LT(ck.totals.spilled, whole.spilled) << "and more goes after it";
    opt.resume = true;
    const BakeSummary resumed = runBake(scene, opt);
    EXPECT_EQ(bytes(opt.output), bytes(ref.output));
    EXPECT_EQ(resumed.spilled, whole.spilled);
    EXPECT_EQ(resumed.warnings, whole.warnings);
    EXPECT_EQ(resumed.end.water, whole.end.water);
}
