#include "cache_test_util.h"

#include "swell/cache/error.h"
#include "swell/cache/reader.h"
#include "swell/cache/writer.h"

#include <csignal>
#include <sys/wait.h>

using namespace swell::cache;
using namespace swell::cache::testing;

namespace {

std::vector<fs::path> listDir(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(dir))
        out.push_back(e.path().filename());
    return out;
}

} // namespace

TEST(Writer, FileAppearsOnlyOnFinish) {
    TempDir dir;
    const auto w = smallWave();
    const fs::path p = dir / "a.swell";
    {
        Writer writer(p, headerFor(w));
        writer.addFrame(syntheticFrame(w, 0));
        EXPECT_FALSE(fs::exists(p));
        ASSERT_EQ(listDir(dir.path()).size(), 1u); // only the temporary file
        EXPECT_NE(listDir(dir.path())[0].string().find(".tmp-"), std::string::npos);
        writer.finish();
        EXPECT_TRUE(fs::exists(p));
    }
    EXPECT_EQ(listDir(dir.path()).size(), 1u);
    EXPECT_EQ(Reader(p).frameCount(), 1u);
}

TEST(Writer, DestroyedBeforeFinishLeavesNothing) {
    TempDir dir;
    const auto w = smallWave();
    {
        Writer writer(dir / "a.swell", headerFor(w));
        writer.addFrame(syntheticFrame(w, 0));
    }
    EXPECT_TRUE(listDir(dir.path()).empty());
}

/// A finished cache of `frames` synthetic frames at dir / "a.swell", and its bytes.
struct ExistingCache {
    TempDir dir;
    SyntheticWave w = smallWave();
    fs::path p = dir / "a.swell";
    std::vector<std::uint8_t> before;
    explicit ExistingCache(std::size_t frames) {
        writeSynthetic(p, headerFor(w), w, frames);
        before = readBytes(p);
    }
};

TEST(Writer, UnfinishedWriteNeverClobbersExistingFile) {
    const ExistingCache c(3);
    const auto& [dir, w, p, before] = c;
    {
        Writer writer(p, headerFor(w));
        writer.addFrame(syntheticFrame(w, 7));
        EXPECT_EQ(readBytes(p), before);
    }
    EXPECT_EQ(readBytes(p), before);
    EXPECT_EQ(Reader(p).frameCount(), 3u);
}

TEST(Writer, KilledProcessLeavesNoFileAtFinalPath) {
    const ExistingCache c(2);
    const auto& [dir, w, p, before] = c;
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) { // child: stream frames, then die mid-write
        Writer writer(p, headerFor(w));
        for (std::size_t i = 0; i < 50; ++i)
            writer.addFrame(syntheticFrame(w, i));
        ::raise(SIGKILL);
        ::_exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(readBytes(p), before); // the good file is untouched
    // The only other thing left is the dead writer's temporary, which never looks whole.
    for (const auto& name : listDir(dir.path()))
        if (name != "a.swell") {
            EXPECT_NE(name.string().find(".tmp-"), std::string::npos);
            EXPECT_THROW(Reader(dir.path() / name), CacheError);
        }
}

TEST(Writer, RejectsMalformedFrames) {
    TempDir dir;
    const auto w = smallWave();
    Writer writer(dir / "a.swell", headerFor(w));
    Frame odd;
    odd.surface = {0.1f, 0.2f, 0.3f};
    EXPECT_THROW(writer.addFrame(odd), std::invalid_argument);
    Frame badSplash;
    badSplash.splash = {0.1f, 0.2f, 0.3f};
    EXPECT_THROW(writer.addFrame(badSplash), std::invalid_argument);
    Frame nan;
    nan.surface = {0.1f, std::numeric_limits<float>::quiet_NaN()};
    EXPECT_THROW(writer.addFrame(nan), std::invalid_argument);
    Frame outside;
    outside.surface = {1000.0f, 0.2f};
    EXPECT_THROW(writer.addFrame(outside), std::invalid_argument);
    Frame infVel;
    infVel.splash = {0.1f, 0.2f, std::numeric_limits<float>::infinity(), 0.0f};
    EXPECT_THROW(writer.addFrame(infVel), std::invalid_argument);
    EXPECT_EQ(writer.frameCount(), 0u);
}

TEST(Writer, RejectsInvalidHeader) {
    TempDir dir;
    Header h;
    h.domain = {0, 0, 0, 1};
    EXPECT_THROW(Writer(dir / "a.swell", h), std::invalid_argument);
    h = Header{};
    h.dt = -1;
    EXPECT_THROW(Writer(dir / "a.swell", h), std::invalid_argument);
    h = Header{};
    h.frameInterval = 0;
    EXPECT_THROW(Writer(dir / "a.swell", h), std::invalid_argument);
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(Writer, UnwritableFolderIsCacheError) {
    EXPECT_THROW(Writer("/nonexistent-dir/a.swell", Header{}), CacheError);
}
