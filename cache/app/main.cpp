// swell-cache: inspect, verify, dump and synthesize .swell caches.
#include "cache_cli.h"
#include "disk_space.h"
#include "exit_codes.h"
#include "swell/cache/error.h"
#include "swell/cache/output_lock.h"
#include "swell/cache/reader.h"
#include "swell/cache/synthetic.h"
#include "swell/cache/writer.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

namespace {
using namespace swell::cache;
using nlohmann::json;

const char* encodingName(Encoding e) {
    return e == Encoding::Float32 ? "float32" : "quantized16";
}

json infoJson(const Reader& r) {
    const Header& h = r.header();
    std::uint64_t surfSum = 0, splashSum = 0, rawSum = 0, compSum = 0;
    std::uint32_t surfMax = 0, splashMax = 0;
    // Splashes come in events (a wave hitting the far wall): how many frames hold any, and
    // the median frame's count, say whether the mean is carried by a few frames.
    std::vector<std::uint32_t> splashCounts;
    splashCounts.reserve(r.frameCount());
    std::size_t splashFrames = 0;
    for (std::size_t i = 0; i < r.frameCount(); ++i) {
        const FrameInfo& e = r.frameInfo(i);
        surfSum += e.surfaceCount;
        splashSum += e.splashCount;
        splashCounts.push_back(e.splashCount);
        splashFrames += e.splashCount > 0 ? 1 : 0;
        surfMax = std::max(surfMax, e.surfaceCount);
        splashMax = std::max(splashMax, e.splashCount);
        rawSum += e.rawSize;
        compSum += e.compressedSize;
    }
    const double n = std::max<double>(1.0, static_cast<double>(r.frameCount()));
    double splashMedian = 0.0;
    if (!splashCounts.empty()) {
        const std::size_t mid = splashCounts.size() / 2;
        std::nth_element(splashCounts.begin(), splashCounts.begin() + mid, splashCounts.end());
        splashMedian = splashCounts[mid];
        if (splashCounts.size() % 2 == 0) {
            const auto below = *std::max_element(splashCounts.begin(), splashCounts.begin() + mid);
            splashMedian = 0.5 * (splashMedian + below);
        }
    }
    json meta = json::parse(h.metadataJson);
    return {
        {"file", r.path().string()},
        {"version", r.version()},
        {"encoding", encodingName(h.encoding)},
        {"shuffle", h.shuffle},
        {"delta", h.delta},
        {"max_position_error_m", h.maxPositionError()},
        {"domain", {h.domain.xMin, h.domain.yMin, h.domain.xMax, h.domain.yMax}},
        {"dt", h.dt},
        {"frame_interval", h.frameInterval},
        {"frame_time", h.frameTime()},
        {"seed", h.seed},
        {"frames", r.frameCount()},
        {"surface_mean", static_cast<double>(surfSum) / n},
        {"surface_max", surfMax},
        {"splash_mean", static_cast<double>(splashSum) / n},
        {"splash_max", splashMax},
        {"splash_frames", splashFrames},
        {"splash_median", splashMedian},
        {"bytes_on_disk", r.fileSize()},
        {"raw_bytes", rawSum},
        {"compressed_frame_bytes", compSum},
        {"compression_ratio", compSum ? static_cast<double>(rawSum) / compSum : 0.0},
        {"metadata", meta},
    };
}

void printInfo(const json& j) {
    fmt::print("file               {}\n", j["file"].get<std::string>());
    fmt::print("format version     {}\n", j["version"].get<int>());
    fmt::print("encoding           {} (shuffle {}, delta {}), max position error {:.3g} m\n",
               j["encoding"].get<std::string>(), j["shuffle"].get<bool>() ? "on" : "off",
               j["delta"].get<bool>() ? "on" : "off", j["max_position_error_m"].get<double>());
    fmt::print("frames             {} every {} steps of {} s ({} s apart)\n",
               j["frames"].get<std::size_t>(), j["frame_interval"].get<unsigned>(),
               j["dt"].get<double>(), j["frame_time"].get<double>());
    fmt::print("surface particles  mean {:.1f}, max {}\n", j["surface_mean"].get<double>(),
               j["surface_max"].get<unsigned>());
    fmt::print("splash particles   mean {:.1f}, max {}, median {:g}; in {} of {} frames\n",
               j["splash_mean"].get<double>(), j["splash_max"].get<unsigned>(),
               j["splash_median"].get<double>(), j["splash_frames"].get<std::size_t>(),
               j["frames"].get<std::size_t>());
    fmt::print("bytes on disk      {}\n", j["bytes_on_disk"].get<std::uint64_t>());
    fmt::print("raw frame bytes    {} (compression ratio {:.2f})\n",
               j["raw_bytes"].get<std::uint64_t>(), j["compression_ratio"].get<double>());
    fmt::print("seed               {}\n", j["seed"].get<std::uint64_t>());
    // The bake's "replay" block (docs/cache-format.md), when this cache has one.
    const json& meta = j["metadata"];
    if (!meta.is_object() || !meta.contains("replay") || !meta["replay"].is_object())
        return;
    const json& r = meta["replay"];
    const auto number = [&](const char* key) {
        return r.contains(key) && r[key].is_number() ? fmt::format("{:g}", r[key].get<double>())
                                                     : std::string("?");
    };
    fmt::print("water extent       x {} .. {} m, still water at y = {} m, particle spacing {} m\n",
               number("water_x_min"), number("water_x_max"), number("still_water_level"),
               number("particle_spacing"));
    fmt::print("steady from        {} s ({})\n", number("steady_start_s"),
               r.contains("steady_reason") && r["steady_reason"].is_string()
                   ? r["steady_reason"].get<std::string>()
                   : std::string("no reason given"));
}

void runVerify(const CacheOptions& o) {
    Reader r(o.path);
    std::uint64_t particles = 0;
    for (std::size_t i = 0; i < r.frameCount(); ++i) {
        const Frame f = r.readFrame(i);
        particles += f.surfaceCount() + f.splashCount();
        // A NaN or infinity (position or splash velocity) is damage too.
        const auto bad = [](float v) { return !std::isfinite(v); };
        if (std::any_of(f.surface.begin(), f.surface.end(), bad) ||
            std::any_of(f.splash.begin(), f.splash.end(), bad))
            throw CacheError(
                fmt::format("{}: frame {}: holds a non-finite value (NaN or infinity)", o.path, i));
        // Every position inside the header's domain (docs/cache-format.md; the writer's rule).
        const Domain& d = r.header().domain;
        const auto refuse = [&](const char* kind, std::size_t k, float x, float y) {
            throw CacheError(fmt::format("{}: frame {}: {} particle {} at ({}, {}) is outside the "
                                         "header's domain x {} .. {}, y {} .. {}",
                                         o.path, i, kind, k, x, y, d.xMin, d.xMax, d.yMin, d.yMax));
        };
        for (std::size_t k = 0; k < f.surfaceCount(); ++k) {
            if (!d.contains(f.surface[2 * k], f.surface[2 * k + 1]))
                refuse("surface", k, f.surface[2 * k], f.surface[2 * k + 1]);
        }
        for (std::size_t k = 0; k < f.splashCount(); ++k) {
            if (!d.contains(f.splash[4 * k], f.splash[4 * k + 1]))
                refuse("splash", k, f.splash[4 * k], f.splash[4 * k + 1]);
        }
    }
    if (o.asJson)
        std::cout << json{{"file", o.path},
                          {"ok", true},
                          {"frames", r.frameCount()},
                          {"particles", particles},
                          {"nonfinite", 0}}
                         .dump()
                  << "\n";
    else
        fmt::print("{}: OK, {} frames, {} particles, every checksum matches\n", o.path,
                   r.frameCount(), particles);
}

void runDump(const CacheOptions& o) {
    Reader r(o.path);
    if (o.frameIndex >= r.frameCount())
        throw CacheError(fmt::format("{}: frame {} does not exist (the cache has {})", o.path,
                                     o.frameIndex, r.frameCount()));
    const Frame f = r.readFrame(o.frameIndex);
    fmt::print("kind,x,y,vx,vy\n");
    for (std::size_t i = 0; i < f.surfaceCount(); ++i)
        fmt::print("surface,{:.9g},{:.9g},,\n", f.surface[2 * i], f.surface[2 * i + 1]);
    for (std::size_t i = 0; i < f.splashCount(); ++i)
        fmt::print("splash,{:.9g},{:.9g},{:.9g},{:.9g}\n", f.splash[4 * i], f.splash[4 * i + 1],
                   f.splash[4 * i + 2], f.splash[4 * i + 3]);
}

void runRecode(const CacheOptions& o) {
    const Reader r(o.path);
    Header h = r.header();
    o.applyEncoding(h);
    const OutputLock lock(o.recodeOut); // one writer per output, as swell-bake
    Writer w(o.recodeOut, h);
    for (std::size_t i = 0; i < r.frameCount(); ++i)
        w.addFrame(r.readFrame(i));
    w.finish();
    fmt::print(stderr, "wrote {} ({} frames, {}, {} bytes)\n", o.recodeOut, r.frameCount(),
               o.encoding, w.bytesWritten());
}

void runSynth(const CacheOptions& o) {
    const SyntheticWave& wave = o.wave;
    const double frameBytes = 96.0 + 40.0 + 8.0 * static_cast<double>(wave.surfaceCount) +
                              16.0 * static_cast<double>(wave.splashCount);
    swell::cli::checkDiskSpace("OUT", o.path, static_cast<double>(o.frames) * frameBytes, o.frames,
                               "lower --frames, --surface or --splash");
    Header h;
    o.applyEncoding(h);
    h.domain = syntheticDomain(wave);
    h.dt = 0.001;
    h.frameInterval = static_cast<std::uint32_t>(std::lround(wave.frameTime / h.dt));
    h.seed = wave.seed;
    h.metadataJson = json{{"generator", "swell-cache synth"},
                          {"scene", "synthetic travelling wave"},
                          {"surface_count", wave.surfaceCount},
                          {"splash_count", wave.splashCount},
                          {"length_m", wave.length},
                          {"depth_m", wave.depth},
                          {"amplitude_m", wave.amplitude},
                          {"wavelength_m", wave.wavelength},
                          {"period_s", wave.period},
                          {"replay", syntheticReplayJson(wave)}}
                         .dump();
    const OutputLock lock(o.path); // one writer per output, as swell-bake
    Writer w(o.path, h);
    for (std::size_t i = 0; i < o.frames; ++i)
        w.addFrame(syntheticFrame(wave, i));
    w.finish();
    fmt::print(stderr, "wrote {} ({} frames, {} bytes)\n", o.path, o.frames, w.bytesWritten());
}

void runInfo(const CacheOptions& o) {
    const json j = infoJson(Reader(o.path));
    if (o.asJson)
        std::cout << j.dump() << "\n";
    else
        printInfo(j);
}

} // namespace

int main(int argc, char** argv) {
    CacheOptions o;
    CacheCommand command = CacheCommand::Info;
    if (const auto rc = parseCacheCommandLine(argc, argv, o, command, std::cout, std::cerr))
        return *rc;
    try {
        const std::pair<CacheCommand, void (*)(const CacheOptions&)> commands[] = {
            {CacheCommand::Info, runInfo},
            {CacheCommand::Verify, runVerify},
            {CacheCommand::Dump, runDump},
            {CacheCommand::Recode, runRecode},
            {CacheCommand::Synth, runSynth}};
        for (const auto& [which, run] : commands) {
            if (which == command)
                run(o);
        }
    } catch (const std::exception& e) {
        fmt::print(stderr, "swell-cache: {}\n", e.what());
        return swell::cli::exitCodeFor(e);
    }
    return swell::cli::kExitOk;
}
