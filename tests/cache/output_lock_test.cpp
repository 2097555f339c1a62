// The output lock (output_lock.h) between two real processes: the second is refused with one
// line naming the holder's PID and the lock file; a holder killed with SIGKILL leaves nothing
// that blocks (the kernel drops its lock). And the names of temporary files.
#include <csignal>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "swell/cache/output_lock.h"
#include "temp_dir.h"

using namespace swell::cache;
namespace fs = std::filesystem;

namespace {

/// A child process that holds the lock of `output` until killed; returns once it holds it.
pid_t holdLockInChild(const fs::path& output) {
    int ready[2];
    if (::pipe(ready) != 0)
        return -1;
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(ready[0]);
        try {
            const OutputLock lock(output);
            (void)!::write(ready[1], "1", 1);
            for (;;)
                ::pause();
        } catch (...) {
            (void)!::write(ready[1], "0", 1);
        }
        ::_exit(1);
    }
    ::close(ready[1]);
    char c = 0;
    const bool held = ::read(ready[0], &c, 1) == 1 && c == '1';
    ::close(ready[0]);
    if (!held) {
        ::waitpid(pid, nullptr, 0);
        return -1;
    }
    return pid;
}

std::string busyMessage(const fs::path& output) {
    try {
        const OutputLock lock(output);
    } catch (const OutputBusy& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(OutputLock, SecondProcessIsRefusedNamingTheHolder) {
    swell::test::TempDir dir;
    const fs::path out = dir.path() / "a.swell";
    for (int trial = 0; trial < 5; ++trial) {
        const pid_t holder = holdLockInChild(out);
        ASSERT_GT(holder, 0);
        const std::string m = busyMessage(out);
        EXPECT_EQ(m, out.string() + ": in use by process " + std::to_string(holder) + " (lock " +
                         lockPath(out).string() +
                         "); wait for it to finish or write to another output");
        ::kill(holder, SIGKILL);
        ::waitpid(holder, nullptr, 0);
        // The kernel released the killed holder's lock: the next writer gets it at once.
        EXPECT_EQ(busyMessage(out), "");
    }
    EXPECT_FALSE(fs::exists(lockPath(out))) << "the last holder removed the lock file";
}

TEST(OutputLock, ReleasedLockIsFreeAndItsFileGone) {
    swell::test::TempDir dir;
    const fs::path out = dir.path() / "b.swell";
    {
        const OutputLock lock(out);
        EXPECT_TRUE(fs::exists(lockPath(out)));
    }
    EXPECT_FALSE(fs::exists(lockPath(out)));
    const pid_t holder = holdLockInChild(out); // another process can take it now
    ASSERT_GT(holder, 0);
    ::kill(holder, SIGKILL);
    ::waitpid(holder, nullptr, 0);
}

TEST(OutputLock, UncreatableLockFileIsACacheError) {
    EXPECT_THROW(OutputLock("/nonexistent-dir/x.swell"), CacheError);
}

TEST(TemporaryFiles, WriterPidComesFromTheName) {
    EXPECT_EQ(temporaryFileWriter("d/a.swell.tmp-123"), 123);
    EXPECT_EQ(temporaryFileWriter("a.swell.ckpt.tmp-7"), 7);
    EXPECT_EQ(temporaryFileWriter("a.swell"), 0);
    EXPECT_EQ(temporaryFileWriter("a.swell.tmp-"), 0);
    EXPECT_EQ(temporaryFileWriter("a.swell.tmp-12x"), 0);
    EXPECT_EQ(temporaryFileWriter(".tmp-12"), 0);
    EXPECT_TRUE(processExists(::getpid()));
    EXPECT_FALSE(processExists(999999999));
}
