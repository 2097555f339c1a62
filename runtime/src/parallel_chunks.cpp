#include "swell/runtime/parallel_chunks.h"

#include <algorithm>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace swell::runtime {

void forEachChunk(std::size_t n, std::size_t chunks,
                  const std::function<void(std::size_t, std::size_t, std::size_t)>& f) {
    chunks = std::max<std::size_t>(chunks, 1);
    std::vector<std::exception_ptr> errors(chunks);
    auto run = [&](std::size_t c) {
        try {
            f(c, n * c / chunks, n * (c + 1) / chunks);
        } catch (...) {
            errors[c] = std::current_exception();
        }
    };
    std::vector<std::thread> threads;
    threads.reserve(chunks - 1);
    for (std::size_t c = 1; c < chunks; ++c) {
        try {
            threads.emplace_back(run, c);
        } catch (const std::system_error&) {
            run(c); // no thread to be had: do it here
        }
    }
    run(0);
    for (std::thread& t : threads)
        t.join();
    for (const std::exception_ptr& e : errors) {
        if (e)
            std::rethrow_exception(e);
    }
}

std::size_t chunkCount(std::size_t n, std::size_t minPerChunk) {
    const std::size_t cores = std::max<std::size_t>(std::thread::hardware_concurrency(), 1);
    const std::size_t bySize = n / std::max<std::size_t>(minPerChunk, 1);
    return std::clamp<std::size_t>(bySize, 1, cores);
}

} // namespace swell::runtime
