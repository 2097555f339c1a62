// Checkpoint files: every field round-trips, writing is atomic (no temporary left, an old
// checkpoint replaced whole), and a missing, truncated, damaged or foreign file is refused
// with an error naming it; a different bake is refused naming the value that differs. Format
// version 2 (before water could be removed) still reads.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <xxhash.h>
#include <zstd.h>

#include "expect_same_particles.h"
#include "swell/bake/checkpoint.h"
#include "temp_dir.h"

using namespace swell::bake;
namespace fs = std::filesystem;

namespace {

Checkpoint sample() {
    Checkpoint c;
    c.fingerprint = R"({"numerics_version":1,"scene":{"solver":{"dt":0.002}},"threads":"any"})";
    c.checkpointEvery = 50;
    c.writerPid = 4242;
    MpsState& s = c.solver;
    s.step = 150;
    s.time = 0.3;
    s.lastMaxSpeed = 0.25;
    s.particles.add(0.01, 0.02, ParticleKind::Water);
    s.particles.add(0.03, 0.04, ParticleKind::Wall);
    s.particles.add(0.05, 0.06, ParticleKind::Dummy);
    s.particles.vx = {0.1, 0.0, 0.0};
    s.particles.vy = {-0.2, 0.0, 0.0};
    s.particles.p = {123.5, 50.25, 0.0};
    s.particles.n = {6.5, 5.0, 4.0};
    s.neighborX = {0.011, 0.03, 0.05};
    s.neighborY = {0.021, std::numeric_limits<double>::quiet_NaN(), 0.06};
    s.wallRestX = {0.0, 0.025, 0.05};
    c.frames.resize(4);
    c.frames[1].surface = {0.1f, 0.2f, 0.3f, 0.4f};
    c.frames[2].splash = {0.5f, 0.6f, 1.0f, -1.0f};
    c.probeRows = {"0,1,2", "0.02,1,nan", "0.04,1,2", "0.06,1,3"};
    c.totals = BakeTotals{10.0, 2.0, 7, 96, 1.5, 300.0, 0.12, 3, 5, 12, 2, 0.25};
    s.removedWater = {1, 4};
    return c;
}

std::string bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, const std::string& b) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << b;
}

class CheckpointFile : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = m_tmp.path();
        m_path = checkpointPath(m_dir / "c.swell");
    }
    /// The CheckpointError message of reading m_path ("" if it reads).
    std::string readError() const {
        try {
            (void)readCheckpoint(m_path);
        } catch (const CheckpointError& e) {
            return e.what();
        }
        return "";
    }
    swell::test::TempDir m_tmp{"swell_checkpoint_"};
    fs::path m_dir, m_path;
};

} // namespace

TEST(CheckpointPath, IsTheCachePathPlusCkpt) {
    EXPECT_EQ(checkpointPath("out/a.swell"), fs::path("out/a.swell.ckpt"));
}

TEST_F(CheckpointFile, EveryFieldRoundTrips) {
    const Checkpoint c = sample();
    const std::uint64_t size = writeCheckpoint(m_path, c);
    EXPECT_EQ(size, fs::file_size(m_path));
    const Checkpoint r = readCheckpoint(m_path);
    EXPECT_EQ(r.fingerprint, c.fingerprint);
    EXPECT_EQ(r.checkpointEvery, 50);
    EXPECT_EQ(r.writerPid, 4242);
    EXPECT_EQ(r.solver.step, 150);
    EXPECT_EQ(r.solver.time, 0.3);
    EXPECT_EQ(r.solver.lastMaxSpeed, 0.25);
    expectSameParticles(r.solver.particles, c.solver.particles);
    EXPECT_EQ(r.solver.neighborX, c.solver.neighborX);
    ASSERT_EQ(r.solver.neighborY.size(), 3u);
    EXPECT_TRUE(std::isnan(r.solver.neighborY[1])); // a stale neighbour reference survives
    EXPECT_EQ(r.solver.neighborY[2], 0.06);
    EXPECT_EQ(r.solver.wallRestX, c.solver.wallRestX);
    EXPECT_EQ(r.frames, c.frames);
    EXPECT_EQ(r.probeRows, c.probeRows);
    EXPECT_EQ(r.totals.surface, 10.0);
    EXPECT_EQ(r.totals.splash, 2.0);
    EXPECT_EQ(r.totals.keptMax, 7u);
    EXPECT_EQ(r.totals.rawBytes, 96u);
    EXPECT_EQ(r.totals.solverSeconds, 1.5);
    EXPECT_EQ(r.totals.ppeIterations, 300.0);
    EXPECT_EQ(r.totals.maxCourant, 0.12);
    EXPECT_EQ(r.totals.recycled, 3u);
    EXPECT_EQ(r.totals.splitSteps, 5u);
    EXPECT_EQ(r.totals.substeps, 12u);
    EXPECT_EQ(r.solver.removedWater, (std::vector<std::uint32_t>{1, 4}));
    EXPECT_EQ(r.totals.spilled, 2u);
    EXPECT_EQ(r.totals.firstSpillTime, 0.25);
}

TEST_F(CheckpointFile, VersionTwoCheckpointReadsAsHavingRemovedNoWater) {
    // Format version 2 is version 3 without what 3 appends (the removed water, the spill
    // counters): made here from a version 3 file with none of either, header and all.
    Checkpoint c = sample();
    c.solver.removedWater.clear();
    c.totals.spilled = 0;
    c.totals.firstSpillTime = 0.0;
    writeCheckpoint(m_path, c);
    const std::string v3 = bytes(m_path);
    constexpr std::size_t kHeader = 48;
    std::vector<char> raw(ZSTD_getFrameContentSize(v3.data() + kHeader, v3.size() - kHeader));
    ASSERT_EQ(ZSTD_decompress(raw.data(), raw.size(), v3.data() + kHeader, v3.size() - kHeader),
              raw.size());
    raw.resize(raw.size() - 3 * 8); // an empty vector's length, a count and a time
    std::string v2(kHeader + ZSTD_compressBound(raw.size()), '\0');
    const std::size_t packed =
        ZSTD_compress(v2.data() + kHeader, v2.size() - kHeader, raw.data(), raw.size(), 3);
    v2.resize(kHeader + packed);
    const auto put = [&](std::size_t at, auto value) {
        std::memcpy(&v2[at], &value, sizeof value);
    };
    std::memcpy(v2.data(), v3.data(), 8); // magic
    put(8, std::uint32_t{2});
    put(12, std::uint32_t{0});
    put(16, std::uint64_t{packed});
    put(24, std::uint64_t{raw.size()});
    put(32, std::uint64_t{XXH3_64bits(v2.data() + kHeader, packed)});
    put(40, std::uint64_t{XXH3_64bits(v2.data(), 40)});
    writeBytes(m_path, v2);

    const Checkpoint r = readCheckpoint(m_path);
    EXPECT_EQ(r.solver.step, 150);
    expectSameParticles(r.solver.particles, c.solver.particles);
    EXPECT_EQ(r.frames, c.frames);
    EXPECT_EQ(r.probeRows, c.probeRows);
    EXPECT_EQ(r.totals.substeps, 12u);
    EXPECT_TRUE(r.solver.removedWater.empty());
    EXPECT_EQ(r.totals.spilled, 0u);

    put(8, std::uint32_t{4}); // a version from the future
    put(40, std::uint64_t{XXH3_64bits(v2.data(), 40)});
    writeBytes(m_path, v2);
    EXPECT_NE(readError().find("format version 4; this swell-bake reads versions 2 to 3"),
              std::string::npos)
        << readError();
}

TEST_F(CheckpointFile, WritingReplacesTheOldFileWholeAndLeavesNoTemporary) {
    Checkpoint c = sample();
    writeCheckpoint(m_path, c);
    c.solver.step = 200;
    c.frames.emplace_back();
    c.probeRows.emplace_back("0.08,1,2");
    writeCheckpoint(m_path, c);
    EXPECT_EQ(readCheckpoint(m_path).solver.step, 200);
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(m_dir)) {
        ++files;
        EXPECT_EQ(e.path(), m_path);
    }
    EXPECT_EQ(files, 1u);
}

TEST_F(CheckpointFile, UnwritableDirectoryNamesTheFile) {
    try {
        writeCheckpoint(m_dir / "no" / "such" / "c.ckpt", sample());
        FAIL() << "wrote into a missing directory";
    } catch (const CheckpointError& e) {
        EXPECT_NE(std::string(e.what()).find("c.ckpt"), std::string::npos) << e.what();
    }
}

TEST_F(CheckpointFile, MissingFileIsNamed) {
    const std::string e = readError();
    EXPECT_NE(e.find(m_path.string()), std::string::npos) << e;
    EXPECT_NE(e.find("no checkpoint"), std::string::npos) << e;
}

TEST_F(CheckpointFile, TruncatedFileIsDamagedAndNamed) {
    writeCheckpoint(m_path, sample());
    const std::string whole = bytes(m_path);
    for (std::size_t keep : {std::size_t{0}, std::size_t{10}, std::size_t{47}, std::size_t{48},
                             whole.size() / 2, whole.size() - 1}) {
        SCOPED_TRACE(keep);
        writeBytes(m_path, whole.substr(0, keep));
        const std::string e = readError();
        EXPECT_EQ(e.rfind(m_path.string() + ": ", 0), 0u) << e;
        EXPECT_NE(e.find("damaged"), std::string::npos) << e;
    }
}

TEST_F(CheckpointFile, AnyFlippedByteIsDetected) {
    writeCheckpoint(m_path, sample());
    const std::string whole = bytes(m_path);
    for (std::size_t at = 0; at < whole.size(); at += 7) {
        SCOPED_TRACE(at);
        std::string b = whole;
        b[at] = static_cast<char>(b[at] ^ 0x10);
        writeBytes(m_path, b);
        const std::string e = readError();
        EXPECT_EQ(e.rfind(m_path.string() + ": ", 0), 0u) << e;
    }
}

TEST_F(CheckpointFile, OtherFileIsNotACheckpoint) {
    writeBytes(m_path, std::string(100, 'x'));
    EXPECT_NE(readError().find("not a swell-bake checkpoint"), std::string::npos) << readError();
}

TEST_F(CheckpointFile, FingerprintOfADifferentBakeNamesTheValue) {
    const std::string stored = sample().fingerprint;
    EXPECT_NO_THROW(checkFingerprint(m_path, stored, stored));
    const auto message = [&](const std::string& current) -> std::string {
        try {
            checkFingerprint(m_path, stored, current);
        } catch (const CheckpointError& e) {
            return e.what();
        }
        return "";
    };
    const std::string dt =
        message(R"({"numerics_version":1,"scene":{"solver":{"dt":0.001}},"threads":"any"})");
    EXPECT_EQ(dt.rfind(m_path.string() + ": ", 0), 0u) << dt;
    EXPECT_NE(dt.find("/scene/solver/dt is 0.002 there, 0.001 now"), std::string::npos) << dt;
    const std::string threads =
        message(R"({"numerics_version":1,"scene":{"solver":{"dt":0.002}},"threads":1})");
    EXPECT_NE(threads.find("/threads is \"any\" there, 1 now"), std::string::npos) << threads;
    const std::string overrides = message(
        R"({"numerics_version":1,"overrides":["a=1"],"scene":{"solver":{"dt":0.002}},"threads":"any"})");
    EXPECT_NE(overrides.find("/overrides is absent there, [\"a=1\"] now"), std::string::npos)
        << overrides;
    // Another numerics version is refused with that reason, whatever else differs.
    const std::string numerics =
        message(R"({"numerics_version":2,"scene":{"solver":{"dt":0.001}},"threads":"any"})");
    EXPECT_NE(numerics.find("numerics version 1, this swell-bake has 2"), std::string::npos)
        << numerics;
    // A checkpoint of a swell-bake from before numerics versions: refused with that reason.
    try {
        checkFingerprint(m_path, R"({"build":"abc","cache_metadata":{}})", stored);
        ADD_FAILURE() << "an old checkpoint was accepted";
    } catch (const CheckpointError& e) {
        EXPECT_NE(std::string(e.what()).find("numerics version none (an older swell-bake)"),
                  std::string::npos)
            << e.what();
    }
}
