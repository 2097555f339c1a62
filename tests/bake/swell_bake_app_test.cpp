// swell-bake end to end: help, bad input (one line, non-zero exit), a small bake verified by
// swell-cache, --json keys, kill safety (SIGKILL / SIGINT / SIGTERM leave no cache), and
// checkpoint / resume (a bake killed after a checkpoint resumes to the same bytes).
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "app_runner.h"
#include "temp_dir.h"

namespace fs = std::filesystem;

namespace {

const fs::path kScenes = SWELL_SCENES_DIR;

using Result = swell::test::AppResult;
using swell::test::slurp;

int lines(const std::string& s) {
    int n = 0;
    for (char c : s)
        n += c == '\n';
    return n;
}

/// Lines that are not warnings (a scene's breaking-wave warning comes before the bake starts).
int errorLines(const std::string& s) {
    std::istringstream in(s);
    int n = 0;
    for (std::string line; std::getline(in, line);)
        n += line.rfind("swell-bake: warning:", 0) != 0;
    return n;
}

class SwellBakeApp : public ::testing::Test {
protected:
    void SetUp() override { m_dir = m_tmp.path(); }

    /// Runs a program; its stdout and stderr pass through a folder of their own, so m_dir
    /// holds only what the program writes.
    Result run(const std::string& exe, const std::string& args) const {
        return swell::test::runApp(exe, args, "", m_io.path());
    }
    Result bake(const std::string& args) const { return run(SWELL_BAKE_EXE, args); }

    /// Starts a long bake in the background and waits until its temporary cache exists.
    pid_t startLongBake(const fs::path& output) const {
        const pid_t pid = ::fork();
        if (pid == 0) {
            const std::string scene = (kScenes / "surging_small.json").string();
            const std::string err = (m_dir / "bake.err").string();
            std::freopen(err.c_str(), "w", stderr);
            ::execl(SWELL_BAKE_EXE, SWELL_BAKE_EXE, scene.c_str(), "-o", output.c_str(), "--set",
                    "solver.end_time=100", "--threads", "1", static_cast<char*>(nullptr));
            ::_exit(127);
        }
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (std::chrono::steady_clock::now() < deadline) {
            for (const auto& e : fs::directory_iterator(m_dir)) {
                if (e.path().filename().string().rfind(output.filename().string() + ".tmp", 0) == 0)
                    return pid;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        ADD_FAILURE() << "the bake never opened its temporary cache";
        return pid;
    }
    std::size_t cacheFiles() const {
        std::size_t n = 0;
        for (const auto& e : fs::directory_iterator(m_dir))
            n += e.path().filename().string().rfind("k.swell", 0) == 0;
        return n;
    }
    swell::test::TempDir m_tmp{"swell_bake_app_"};
    swell::test::TempDir m_io{"swell_bake_app_io_"};
    fs::path m_dir;
};

} // namespace

TEST_F(SwellBakeApp, HelpListsTheOptions) {
    const Result r = bake("--help");
    EXPECT_EQ(r.code, 0);
    for (const char* o : {"--output", "--set", "--threads", "--probes", "--json",
                          "--checkpoint-every", "--resume"}) {
        EXPECT_NE(r.out.find(o), std::string::npos) << o;
    }
}

TEST_F(SwellBakeApp, BadInputGivesOneLineAndNonZeroExit) {
    const std::string out = (m_dir / "x.swell").string();
    const std::string small = (kScenes / "surging_small.json").string();
    struct Case {
        std::string args, expect;
    };
    const Case cases[] = {
        {"/no/such/scene.json -o " + out, "cannot open scene file"},
        {small, "--output"},                                          // missing -o
        {small + " -o " + out + " --set solver.dtt=1", "solver.dtt"}, // unknown key
        {small + " -o " + out + " --set piston.kind=wobbly", "piston.kind"},
        {small + " -o " + out + " --set output.frame_interval=0.003", "output.frame_interval"},
        {small + " -o " + out + " --set nonsense", "section.key=value"},
        {small + " -o " + out + " --threads 0", "--threads"},
        {small + " -o " + out + " --checkpoint-every 0", "--checkpoint-every"},
        {small + " -o /no/such/dir/x.swell", "the folder /no/such/dir does not exist"},
        {small + " -o " + m_dir.string(), "is a directory; give the cache's file name"},
        {small + " -o " + out + " --set output.frame_interval=2147483.6485", "at most 1e9 steps"},
        {m_dir.string() + " -o " + out, "is a directory, not a JSON file"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.args);
        const Result r = bake(c.args);
        EXPECT_EQ(r.code, 2); // README "Exit statuses": a bad command line or scene
        EXPECT_EQ(errorLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
        EXPECT_TRUE(r.out.empty());
    }
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(SwellBakeApp, SmallSurgingBakeVerifiesAndPrintsTheJsonSummary) {
    const fs::path out = m_dir / "s.swell";
    const fs::path csv = m_dir / "s.csv";
    const Result r =
        bake((kScenes / "surging_small.json").string() + " -o " + out.string() + " --probes " +
             csv.string() + " --set solver.end_time=0.5 --threads 1 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    for (const char* k : {"particles_water", "particles_wall", "steps", "frames", "surface_mean",
                          "splash_mean", "reduction", "wall_seconds", "ms_per_step"}) {
        EXPECT_TRUE(j.contains(k)) << k;
    }
    EXPECT_EQ(j["steps"], 250);
    EXPECT_EQ(j["frames"], 26);
    EXPECT_NE(r.err.find("step 250/250"), std::string::npos) << r.err; // progress, then the summary
    EXPECT_NE(r.err.find("fewer than water"), std::string::npos) << r.err;
    const Result v = run(SWELL_CACHE_EXE, "verify " + out.string());
    EXPECT_EQ(v.code, 0) << v.out << v.err;
    EXPECT_EQ(lines(slurp(csv)), 27);
}

TEST_F(SwellBakeApp, WaterOverTheWallIsAWarningAndTheCacheIsWritten) {
    // A column twice as tall as the walls against the front wall: its top falls over it.
    const fs::path scene = m_dir / "overfull.json";
    std::ofstream(scene) << R"({"geometry": {"particle_spacing": 0.005,
        "tank": {"x0": 0.0, "y0": 0.0, "x1": 0.3, "y1": 0.1},
        "water": [{"x0": 0.2, "y0": 0.0, "x1": 0.3, "y1": 0.2}],
        "domain": {"x0": -0.2, "y0": -0.2, "x1": 0.6, "y1": 1.0}},
        "solver": {"dt": 0.0005, "end_time": 0.2}, "output": {"frame_interval": 0.01}})";
    const fs::path out = m_dir / "o.swell";
    const Result r = bake(scene.string() + " -o " + out.string() + " --threads 1 --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_GT(j["spilled"].get<int>(), 0);
    EXPECT_EQ(j["conservation"]["water_lost"], j["spilled"]);
    EXPECT_NE(r.err.find("swell-bake: warning: " + std::to_string(j["spilled"].get<int>()) +
                         " water particle(s) went over the tank's walls"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(run(SWELL_CACHE_EXE, "verify " + out.string()).code, 0);
}

TEST_F(SwellBakeApp, KilledBakeLeavesNoCacheAtTheOutputPath) {
    const fs::path out = m_dir / "k.swell";
    const pid_t pid = startLongBake(out);
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status));
    EXPECT_FALSE(
        fs::exists(out)); // (an orphaned temporary may stay; it never looks like the cache)
}

TEST_F(SwellBakeApp, InterruptedBakeStopsCleanlyAndLeavesNothing) {
    for (int sig : {SIGINT, SIGTERM}) {
        SCOPED_TRACE(sig);
        const fs::path out = m_dir / "k.swell";
        const pid_t pid = startLongBake(out);
        ::kill(pid, sig);
        int status = 0;
        ::waitpid(pid, &status, 0);
        ASSERT_TRUE(WIFEXITED(status));
        EXPECT_EQ(WEXITSTATUS(status), 130);
        EXPECT_EQ(cacheFiles(), 0u) << "neither the cache nor its temporary file";
        EXPECT_NE(slurp(m_dir / "bake.err").find("cancelled"), std::string::npos);
    }
}

// SIGKILL after a checkpoint exists, then --resume: the cache is byte-identical to
// an uninterrupted bake, the checkpoint and the killed run's temporaries are gone.
TEST_F(SwellBakeApp, BakeKilledAfterACheckpointResumesToTheSameCache) {
    const std::string scene = (kScenes / "surging_small.json").string();
    const std::string common = " --set solver.end_time=1.5 --threads 1 -q";
    const fs::path ref = m_dir / "ref.swell", out = m_dir / "s.swell";
    ASSERT_EQ(bake(scene + " -o " + ref.string() + common).code, 0);

    const fs::path ckpt = m_dir / "s.swell.ckpt";
    const pid_t pid = ::fork();
    if (pid == 0) {
        const std::string err = (m_dir / "bake.err").string();
        std::freopen(err.c_str(), "w", stderr);
        ::execl(SWELL_BAKE_EXE, SWELL_BAKE_EXE, scene.c_str(), "-o", out.c_str(), "--set",
                "solver.end_time=1.5", "--threads", "1", "--checkpoint-every", "40",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!fs::exists(ckpt) && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status))
        << "the bake finished before it was killed; " << slurp(m_dir / "bake.err");
    EXPECT_FALSE(fs::exists(out));
    ASSERT_TRUE(fs::exists(ckpt));

    const Result r = bake(scene + " -o " + out.string() + common + " --resume --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_GT(nlohmann::json::parse(r.out)["resumed_from_step"].get<long>(), 0);
    EXPECT_EQ(slurp(out), slurp(ref));
    EXPECT_FALSE(fs::exists(ckpt));
    for (const auto& e : fs::directory_iterator(m_dir)) {
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos)
            << e.path(); // stale ones removed
    }
}

TEST_F(SwellBakeApp, SigtermWithCheckpointsSavesOneToResumeFrom) {
    const fs::path out = m_dir / "k.swell";
    const pid_t pid = ::fork();
    if (pid == 0) {
        const std::string scene = (kScenes / "surging_small.json").string();
        const std::string err = (m_dir / "bake.err").string();
        std::freopen(err.c_str(), "w", stderr);
        ::execl(SWELL_BAKE_EXE, SWELL_BAKE_EXE, scene.c_str(), "-o", out.c_str(), "--set",
                "solver.end_time=100", "--threads", "1", "--checkpoint-every", "100000",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(fs::exists(m_dir / "k.swell.ckpt"));
    EXPECT_NE(slurp(m_dir / "bake.err").find("continue with --resume"), std::string::npos)
        << slurp(m_dir / "bake.err");

    // Resuming it as another bake is refused, naming what differs; the checkpoint stays.
    const std::string scene = (kScenes / "surging_small.json").string();
    const std::string base = scene + " -o " + out.string() + " --set solver.end_time=100 --resume";
    Result r = bake(base + " --threads 1 --set physics.kinematic_viscosity=1e-6");
    EXPECT_EQ(r.code, 5);
    EXPECT_EQ(errorLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("k.swell.ckpt: checkpoint of a different bake (/overrides is "
                         "[\"solver.end_time=100\"] there, [\"solver.end_time=100\","
                         "\"physics.kinematic_viscosity=1e-6\"] now)"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(fs::exists(m_dir / "k.swell.ckpt"));
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(SwellBakeApp, ResumeErrorsGiveOneLineAndExitCode5) {
    const std::string scene = (kScenes / "surging_small.json").string();
    const fs::path out = m_dir / "s.swell", ckpt = m_dir / "s.swell.ckpt";
    const std::string base =
        scene + " -o " + out.string() + " --set solver.end_time=0.3 --threads 1";
    Result r = bake(base + " --resume");
    EXPECT_EQ(r.code, 5);
    EXPECT_EQ(errorLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(ckpt.string() + ": no checkpoint"), std::string::npos) << r.err;

    // A truncated checkpoint (right magic, nothing else).
    std::ofstream(ckpt, std::ios::binary) << "\x89SWK\r\n\x1a\ntruncated";
    r = bake(base + " --resume");
    EXPECT_EQ(r.code, 5);
    EXPECT_EQ(errorLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(ckpt.string() + ": damaged checkpoint"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));

    // A fresh bake that would take checkpoints over the one there (another bake's, which it
    // could then lose) is refused before it writes anything; the checkpoint stays byte for
    // byte. Without --checkpoint-every it bakes and leaves the checkpoint alone.
    const std::string before = slurp(ckpt);
    r = bake(base + " --checkpoint-every 50");
    EXPECT_EQ(r.code, 5);
    EXPECT_EQ(errorLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(ckpt.string() + ": a checkpoint of an earlier bake is there"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(slurp(ckpt), before);
    r = bake(base + " -q");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(slurp(ckpt), before);
}

// Two writers of one output: while a swell-bake holds the output (its temporary cache exists),
// a second swell-bake to it, with or without --resume, exits 6 with one line naming the first's
// PID and the lock file, and touches nothing; after the first is killed with SIGKILL the lock
// is gone with it and the next bake runs.
TEST_F(SwellBakeApp, SecondWriterOfAnOutputIsRefusedNamingTheFirst) {
    const fs::path out = m_dir / "k.swell";
    const pid_t first = startLongBake(out);
    const std::string scene = (kScenes / "surging_small.json").string();
    for (const char* extra : {"", " --resume", " --checkpoint-every 10"}) {
        SCOPED_TRACE(extra);
        const Result r =
            bake(scene + " -o " + out.string() + " --set solver.end_time=0.1 -q" + extra);
        EXPECT_EQ(r.code, 6);
        EXPECT_EQ(errorLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(out.string() + ": in use by process " + std::to_string(first) +
                             " (lock " + out.string() + ".lock)"),
                  std::string::npos)
            << r.err;
    }
    EXPECT_FALSE(fs::exists(out));
    ::kill(first, SIGKILL);
    ::waitpid(first, nullptr, 0);
    const Result r = bake(scene + " -o " + out.string() + " --set solver.end_time=0.1 -q");
    EXPECT_EQ(r.code, 0) << r.err;
    for (const auto& e : fs::directory_iterator(m_dir)) // the killed bake's temporary is gone
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// A full disk or an I/O error (SWELL_FAULT_INJECT, checked_write.h) at each write site of a
// bake: the cache, the checkpoint and the probes CSV. Each run stops with one line naming the
// file and the reason and a non-zero exit; the previous good cache, checkpoint and probes are
// byte for byte what they were; no temporary is left. (A fresh bake that takes checkpoints
// runs only where no checkpoint is: at the checkpoint site none is there, and none is left.)
TEST_F(SwellBakeApp, FullDiskOrIoErrorAtEachWriteSiteKeepsThePreviousFiles) {
    const std::string scene = (kScenes / "surging_small.json").string();
    const fs::path out = m_dir / "s.swell", ckpt = m_dir / "s.swell.ckpt", probes = m_dir / "s.csv";
    const std::string args = scene + " -o " + out.string() + " --probes " + probes.string() +
                             " --set solver.end_time=0.4 --threads 1 -q";
    // The previous good files: a cache and probes of an earlier bake, and a checkpoint.
    ASSERT_EQ(bake(args).code, 0);
    std::ofstream(ckpt, std::ios::binary) << "previous checkpoint";
    const std::string cache0 = slurp(out), probes0 = slurp(probes), ckpt0 = slurp(ckpt);
    struct Site {
        const char* match;
        const char* extra;
        int code;
        fs::path named;
        std::vector<const char*> afters; // bytes before the fault: at the start, in the header,
                                         // mid-file (the cache is 8.5 kB, the CSV 1 kB)
    };
    const Site sites[] = {{".swell.tmp", "", 4, out, {"0", "100", "5000"}},
                          {".ckpt.tmp", " --checkpoint-every 50", 5, ckpt, {"0", "100", "5000"}},
                          {".csv.tmp", "", 1, probes, {"0", "100"}}};
    for (const Site& s : sites) {
        for (const char* kind : {"enospc", "eio"}) {
            for (const char* after : s.afters) {
                SCOPED_TRACE(std::string(s.match) + " " + kind + " after " + after);
                const std::string env = std::string("SWELL_FAULT_INJECT=") + kind +
                                        ":after=" + after + ":match=" + s.match;
                // A shorter bake than the first: a cache or probes it wrote would differ.
                const bool checkpoints = *s.extra != '\0';
                if (checkpoints)
                    fs::remove(ckpt);
                const Result r = swell::test::runApp(SWELL_BAKE_EXE,
                                                     args + " --set solver.end_time=0.3" + s.extra,
                                                     env, m_io.path());
                EXPECT_EQ(r.code, s.code) << r.err;
                EXPECT_EQ(errorLines(r.err), 1) << r.err;
                EXPECT_NE(r.err.find(s.named.string()), std::string::npos) << r.err;
                EXPECT_NE(r.err.find(std::string(kind) == "eio" ? "Input/output error"
                                                                : "No space left on device"),
                          std::string::npos)
                    << r.err;
                EXPECT_TRUE(slurp(out) == cache0) << "the previous cache changed";
                EXPECT_TRUE(slurp(probes) == probes0) << "the previous probes changed";
                if (checkpoints) {
                    EXPECT_FALSE(fs::exists(ckpt)) << "a checkpoint that could not be written";
                    std::ofstream(ckpt, std::ios::binary) << ckpt0;
                }
                EXPECT_TRUE(slurp(ckpt) == ckpt0) << "the previous checkpoint changed";
                for (const auto& e : fs::directory_iterator(m_dir))
                    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos)
                        << e.path();
            }
        }
    }
}
