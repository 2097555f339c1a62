// The checked write path (checked_write.h): the injected fault's spec, a write that crosses
// the limit (its first bytes land, then ENOSPC / EIO, and every later write fails), the match
// that picks one write site, and the cache writer reporting it with nothing left behind.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "cache_test_util.h"
#include "swell/cache/checked_write.h"
#include "swell/cache/error.h"
#include "swell/cache/output_lock.h"
#include "swell/cache/writer.h"

using namespace swell::cache;
using namespace swell::cache::testing;

namespace {

std::size_t filesIn(const fs::path& dir) {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}
std::string contents(const fs::path& p) {
    const std::vector<std::uint8_t> b = readBytes(p);
    return {b.begin(), b.end()};
}

class CheckedWrite : public ::testing::Test {
protected:
    void TearDown() override { disarmWriteFault(); }
    TempDir m_tmp;
};

} // namespace

TEST(WriteFaultSpec, ParsesKindBytesAndMatchAndRefusesTheRest) {
    WriteFault f = parseWriteFault("enospc:after=100");
    EXPECT_EQ(f.error, ENOSPC);
    EXPECT_EQ(f.afterBytes, 100u);
    EXPECT_EQ(f.match, "");
    f = parseWriteFault("eio:after=0:match=.ckpt");
    EXPECT_EQ(f.error, EIO);
    EXPECT_EQ(f.afterBytes, 0u);
    EXPECT_EQ(f.match, ".ckpt");
    for (const char* bad : {"", "enospc", "enospc:after=", "enospc:after=-1", "full:after=1",
                            "eio:after=1:match=", "eio:after=1:x=y", "eio:after=1x"}) {
        try {
            parseWriteFault(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("SWELL_FAULT_INJECT"), std::string::npos);
        }
    }
}

TEST_F(CheckedWrite, WriteCrossingTheLimitLandsItsFirstBytesThenFails) {
    const fs::path p = m_tmp.path() / "f";
    armWriteFault({ENOSPC, 5, ""});
    EXPECT_EQ(writeFile(p, "abcdefgh", 8), ENOSPC);
    EXPECT_EQ(fs::file_size(p), 5u); // as a disk that filled up
    EXPECT_EQ(writeFile(p, "x", 1), ENOSPC) << "the disk stays full";
    disarmWriteFault();
    EXPECT_EQ(writeFile(p, "abcdefgh", 8), 0);
    EXPECT_EQ(fs::file_size(p), 8u);
}

TEST_F(CheckedWrite, MatchPicksTheFilesThatFail) {
    armWriteFault({EIO, 0, ".ckpt"});
    EXPECT_EQ(writeFile(m_tmp.path() / "a.swell", "abc", 3), 0);
    EXPECT_EQ(writeFile(m_tmp.path() / "a.swell.ckpt.tmp-1", "abc", 3), EIO);
}

// replaceFile: the new bytes whole, or the old file untouched and no temporary, with the step
// that failed named.
TEST_F(CheckedWrite, ReplaceFileSwapsInTheWholeFileOrLeavesTheOldOne) {
    const fs::path p = m_tmp.path() / "t.txt";
    ReplaceResult r = replaceFile(p, "first", 5);
    EXPECT_EQ(r.error, 0);
    EXPECT_EQ(contents(p), "first");
    r = replaceFile(p, "second", 6);
    EXPECT_EQ(r.error, 0);
    EXPECT_EQ(contents(p), "second");
    EXPECT_EQ(filesIn(m_tmp.path()), 1u);

    armWriteFault({ENOSPC, 3, ""});
    r = replaceFile(p, "third!", 6);
    disarmWriteFault();
    EXPECT_EQ(r.error, ENOSPC);
    EXPECT_STREQ(r.step, "write");
    EXPECT_EQ(r.temporary, temporaryPath(p));
    EXPECT_EQ(contents(p), "second");
    EXPECT_EQ(filesIn(m_tmp.path()), 1u) << "a temporary was left";

    // A folder in the way: the write succeeds, the rename over it fails.
    const fs::path dir = m_tmp.path() / "d";
    fs::create_directories(dir / "inside");
    r = replaceFile(dir, "x", 1);
    EXPECT_NE(r.error, 0);
    EXPECT_STREQ(r.step, "rename");
    EXPECT_TRUE(fs::is_directory(dir));
    EXPECT_EQ(filesIn(m_tmp.path()), 2u) << "a temporary was left";
}

// A full disk while a cache is written: CacheError naming the cache and the reason, the
// previous cache byte for byte, no temporary.
TEST_F(CheckedWrite, CacheWriterReportsAFullDiskAndKeepsThePreviousCache) {
    const fs::path p = m_tmp.path() / "c.swell";
    const SyntheticWave wave = smallWave();
    writeSynthetic(p, headerFor(wave), wave, 3);
    const std::string before = contents(p);
    for (const std::uint64_t after : {0ull, 100ull, 2000ull}) {
        SCOPED_TRACE(after);
        for (const int error : {ENOSPC, EIO}) {
            armWriteFault({error, after, ""});
            try {
                writeSynthetic(p, headerFor(wave), wave, 20);
                ADD_FAILURE() << "no error";
            } catch (const CacheError& e) {
                const std::string m = e.what();
                EXPECT_EQ(m.rfind(p.string() + ": ", 0), 0u) << m;
                EXPECT_NE(m.find(std::strerror(error)), std::string::npos) << m;
            }
            disarmWriteFault();
            EXPECT_EQ(contents(p), before);
            EXPECT_EQ(filesIn(m_tmp.path()), 1u) << "a temporary was left";
        }
    }
}
