// Write and read throughput of the cache format at paper scale: 1,200 frames of
// ~400 surface particles (Table 3: 322 kept particles, surging wave).
// Run: build/bin/swell-cache-bench  (figures recorded in docs/BENCHMARKS.md)
#include "swell/cache/reader.h"
#include "swell/cache/synthetic.h"
#include "swell/cache/writer.h"

#include <benchmark/benchmark.h>
#include <filesystem>
#include <unistd.h>

namespace {
namespace fs = std::filesystem;
using namespace swell::cache;

constexpr std::size_t kFrames = 1200;

SyntheticWave paperWave() {
    SyntheticWave w;
    w.surfaceCount = 400;
    w.splashCount = 8;
    return w;
}

Header headerFor(Encoding enc, bool filters) {
    Header h;
    h.encoding = enc;
    h.shuffle = h.delta = filters;
    h.domain = syntheticDomain(paperWave());
    h.frameInterval = 20;
    return h;
}

fs::path tempPath(const char* name) {
    return fs::temp_directory_path() /
           (std::string(name) + "-" + std::to_string(::getpid()) + ".swell");
}

const std::vector<Frame>& frames() {
    static const std::vector<Frame> f = [] {
        std::vector<Frame> v;
        for (std::size_t i = 0; i < kFrames; ++i)
            v.push_back(syntheticFrame(paperWave(), i));
        return v;
    }();
    return f;
}

void writeCache(const fs::path& p, Encoding enc, bool filters) {
    Writer w(p, headerFor(enc, filters));
    for (const Frame& f : frames())
        w.addFrame(f);
    w.finish();
}

void setCounters(benchmark::State& state, const fs::path& p) {
    const Reader r(p);
    std::uint64_t raw = 0, comp = 0;
    for (std::size_t i = 0; i < r.frameCount(); ++i) {
        raw += r.frameInfo(i).rawSize;
        comp += r.frameInfo(i).compressedSize;
    }
    state.counters["file_MB"] = static_cast<double>(r.fileSize()) / 1e6;
    state.counters["ratio"] = static_cast<double>(raw) / static_cast<double>(comp);
    state.counters["float32_ratio"] =
        static_cast<double>(kFrames * (400 * 8 + 8 * 16)) / static_cast<double>(r.fileSize());
    state.counters["max_pos_err_m"] = r.header().maxPositionError();
}

void BM_Write(benchmark::State& state) {
    const auto enc = static_cast<Encoding>(state.range(0));
    const bool filters = state.range(1) != 0;
    const fs::path p = tempPath("write");
    (void)frames();
    for (auto _ : state)
        writeCache(p, enc, filters);
    const double rawBytes = static_cast<double>(kFrames * (400 * 8 + 8 * 16));
    state.counters["MB_per_s"] = benchmark::Counter(
        rawBytes / 1e6 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
    setCounters(state, p);
    fs::remove(p);
}

void BM_ReadAll(benchmark::State& state) {
    const auto enc = static_cast<Encoding>(state.range(0));
    const bool filters = state.range(1) != 0;
    const fs::path p = tempPath("read");
    writeCache(p, enc, filters);
    for (auto _ : state) {
        const Reader r(p);
        auto all = r.readAll();
        benchmark::DoNotOptimize(all.data());
    }
    setCounters(state, p);
    fs::remove(p);
}

void BM_ReadOneFrame(benchmark::State& state) {
    const fs::path p = tempPath("one");
    writeCache(p, Encoding::Float32, true);
    const Reader r(p);
    std::size_t i = 0;
    for (auto _ : state) {
        auto f = r.readFrame((i++ * 7919) % kFrames);
        benchmark::DoNotOptimize(f.surface.data());
    }
    fs::remove(p);
}

// Args: {encoding (0 float32, 1 quantized16), filters (shuffle+delta on/off)}
BENCHMARK(BM_Write)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadAll)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadOneFrame)->Unit(benchmark::kMicrosecond);

} // namespace

BENCHMARK_MAIN();
