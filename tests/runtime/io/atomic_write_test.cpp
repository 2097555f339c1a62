// Atomic output files (atomic_write.h): complete or absent, never half-written, no temporary
// left behind, an older complete file kept when a rewrite fails.
#include "swell/runtime/error.h"
#include "swell/runtime/io/atomic_write.h"

#include "app_runner.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace swell::runtime {
namespace {

namespace fs = std::filesystem;

std::size_t filesIn(const fs::path& dir) {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

} // namespace

TEST(AtomicWrite, WritesUnderATemporaryNameAndRenamesIt) {
    const swell::test::TempDir temp("swell_atomic_");
    const fs::path path = temp / "a.json";
    fs::path seen;
    writeAtomically(path, [&](const fs::path& temporary) {
        seen = temporary;
        EXPECT_EQ(temporary.parent_path(), temp.path()); // same folder: rename is atomic
        EXPECT_NE(temporary, path);
        std::ofstream(temporary) << "whole";
        EXPECT_FALSE(fs::exists(path)); // nothing under the final name while writing
    });
    EXPECT_EQ(swell::test::slurp(path), "whole");
    EXPECT_FALSE(fs::exists(seen));
    EXPECT_EQ(filesIn(temp.path()), 1u);
}

TEST(AtomicWrite, AFailedWriteLeavesNoPartialFileAndKeepsTheOldOne) {
    const swell::test::TempDir temp("swell_atomic_");
    const fs::path path = temp / "b.txt";
    const auto failing = [](const fs::path& temporary) {
        std::ofstream(temporary) << "half of it";
        throw RuntimeError("disk full");
    };
    EXPECT_THROW(writeAtomically(path, failing), RuntimeError);
    EXPECT_FALSE(fs::exists(path));
    EXPECT_EQ(filesIn(temp.path()), 0u);
    writeTextAtomically(path, "old and complete\n");
    EXPECT_THROW(writeAtomically(path, failing), RuntimeError);
    EXPECT_EQ(swell::test::slurp(path), "old and complete\n");
    EXPECT_EQ(filesIn(temp.path()), 1u);
}

TEST(AtomicWrite, AnUnwritableFolderIsAnErrorNamingTheFile) {
    try {
        writeTextAtomically("/nonexistent-dir/c.json", "{}");
        ADD_FAILURE() << "no error";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/c.json"), std::string::npos)
            << e.what();
    }
    // A folder standing where the file goes: the rename fails, the temporary is removed.
    const swell::test::TempDir temp("swell_atomic_");
    fs::create_directory(temp / "d.json");
    EXPECT_THROW(writeTextAtomically(temp / "d.json", "{}"), RuntimeError);
    EXPECT_EQ(filesIn(temp.path()), 1u);
}

} // namespace swell::runtime

namespace swell::runtime {

// A folder written under DeferredRenames: nothing replaces an old file before commit(); a run
// that ends without commit leaves the folder exactly as it was.
TEST(DeferredRenames, OldFilesStayUntilCommitAndAFailedRunLeavesThemAlone) {
    const swell::test::TempDir temp("swell_atomic_");
    writeTextAtomically(temp / "a", "old a");
    {
        DeferredRenames staged;
        writeTextAtomically(temp / "a", "new a");
        writeTextAtomically(temp / "b", "new b");
        EXPECT_EQ(swell::test::slurp(temp / "a"), "old a");
        EXPECT_FALSE(fs::exists(temp / "b"));
        EXPECT_THROW(DeferredRenames(), std::logic_error); // one per thread
    }                                                      // no commit: a failed run
    EXPECT_EQ(swell::test::slurp(temp / "a"), "old a");
    EXPECT_EQ(filesIn(temp.path()), 1u) << "the temporaries are gone";
    DeferredRenames staged;
    writeTextAtomically(temp / "a", "new a");
    writeTextAtomically(temp / "b", "new b");
    EXPECT_TRUE(staged.deferring());
    staged.commit();
    EXPECT_FALSE(staged.deferring());
    EXPECT_EQ(swell::test::slurp(temp / "a"), "new a");
    EXPECT_EQ(swell::test::slurp(temp / "b"), "new b");
    EXPECT_EQ(filesIn(temp.path()), 2u);
    writeTextAtomically(temp / "c", "direct"); // after commit: written at once again
    EXPECT_EQ(swell::test::slurp(temp / "c"), "direct");
}

} // namespace swell::runtime
