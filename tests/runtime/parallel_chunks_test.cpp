// CPU work split into consecutive ranges over threads (the per-frame splash sprites).
#include "swell/runtime/parallel_chunks.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

namespace swell::runtime {
namespace {

TEST(ParallelChunks, RangesSplitTheWholeInOrder) {
    for (std::size_t n : {0u, 1u, 5u, 1000u, 1001u}) {
        for (std::size_t chunks : {1u, 2u, 3u, 7u}) {
            std::vector<std::size_t> begins(chunks), ends(chunks);
            std::vector<int> seen(n, 0);
            forEachChunk(n, chunks, [&](std::size_t c, std::size_t b, std::size_t e) {
                begins[c] = b;
                ends[c] = e;
                for (std::size_t i = b; i < e; ++i)
                    ++seen[i];
            });
            for (std::size_t c = 0; c < chunks; ++c) {
                EXPECT_EQ(begins[c], n * c / chunks);
                EXPECT_EQ(ends[c], n * (c + 1) / chunks);
            }
            for (std::size_t i = 0; i < n; ++i)
                EXPECT_EQ(seen[i], 1) << "item " << i << " of " << n << " in " << chunks;
        }
    }
}

TEST(ParallelChunks, ChunksRunOnThreadsOfTheirOwnAndTheFirstHere) {
    std::vector<std::thread::id> ids(3);
    forEachChunk(30, 3, [&](std::size_t c, std::size_t, std::size_t) {
        ids[c] = std::this_thread::get_id();
    });
    EXPECT_EQ(ids[0], std::this_thread::get_id());
    EXPECT_NE(ids[1], ids[0]);
    EXPECT_NE(ids[2], ids[0]);
    EXPECT_NE(ids[1], ids[2]);
}

TEST(ParallelChunks, TheFirstFailingChunksErrorComesBackAfterAllFinished) {
    std::atomic<int> finished{0};
    try {
        forEachChunk(40, 4, [&](std::size_t c, std::size_t, std::size_t) {
            if (c == 1 || c == 3)
                throw std::runtime_error("chunk " + std::to_string(c));
            ++finished;
        });
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "chunk 1");
    }
    EXPECT_EQ(finished.load(), 2);
}

TEST(ParallelChunks, ChunkCountKeepsAMinimumPerChunk) {
    const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
    EXPECT_EQ(chunkCount(0, 100), 1u);
    EXPECT_EQ(chunkCount(99, 100), 1u);
    EXPECT_EQ(chunkCount(200, 100), std::min<std::size_t>(2, cores));
    EXPECT_EQ(chunkCount(1000000, 100), cores);
    EXPECT_EQ(chunkCount(10, 0), std::min<std::size_t>(10, cores));
}

} // namespace
} // namespace swell::runtime
