// swell-play: headless replay of a .swell cache (paper Sec. 4): bench and height fields.
// The library does the work; this file parses options, reads the cache, times and prints.

#include "swell/cache/error.h"
#include "swell/cache/reader.h"
#include "swell/runtime/cpu_reconstruction.h"
#include "swell/runtime/egl_context.h"
#include "swell/runtime/error.h"
#include "swell/runtime/gpu_reconstruction.h"
#include "swell/runtime/height_png.h"
#include "swell/runtime/mode_replay.h"
#include "swell/runtime/slice_sampler.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <unistd.h>

namespace {

using namespace swell;
using namespace swell::runtime;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Options shared by every subcommand.
struct Options {
    std::string cache;            ///< input .swell file
    std::string res = "128x128";  ///< N x M base-mesh cells
    std::string policy = "loop";  ///< frames outside the cache: clamp or loop
    std::string filter = "low";   ///< noise band: low, high or none
    std::string mode = "surging"; ///< slice layout: surging, ripple or whirlpool
    double playbackFps = 30.0;    ///< output frames per simulated second
    double start = 0.0;           ///< simulated second of the first output frame
    bool json = false;            ///< one JSON object on stdout
    ReplayParams params;          ///< the replay itself (paper defaults)
    ModeParams modeParams;        ///< ripple directions, whirlpool spirals
    /// Options whose default depends on --mode (Table 4): given explicitly when count() > 0.
    std::vector<std::pair<CLI::Option*, void (*)(ReplayParams&, const ReplayParams&)>> modal;
};

void addCommon(CLI::App* cmd, Options& o) {
    cmd->add_option("CACHE", o.cache, "input .swell cache")->required();
    cmd->add_option("--mode", o.mode,
                    "slice layout: surging (Sec. 4.2), ripple (4.4) or whirlpool (4.5); sets the "
                    "Table 4 defaults of --slices, -F, --beta, --cutoff")
        ->capture_default_str()
        ->check(CLI::IsMember({"surging", "ripple", "whirlpool"}));
    cmd->add_option("--angles", o.modeParams.ripple.anglesDegrees,
                    "ripple: direction angles in degrees from +x towards +z")
        ->capture_default_str();
    cmd->add_option("--weights", o.modeParams.ripple.weights,
                    "ripple: eq. (8) weight per direction (default: the mean)");
    cmd->add_option("--spiral-a", o.modeParams.whirlpool.innerRadiusCells,
                    "whirlpool: inner radius a in cells of dx (paper 15)")
        ->capture_default_str();
    cmd->add_option("--spiral-b", o.modeParams.whirlpool.growth,
                    "whirlpool: growth b per radian (paper 25 dz = 25/128)")
        ->capture_default_str();
    cmd->add_option("--spin", o.modeParams.whirlpool.turnsPerTimeUnit,
                    "whirlpool: turns per animation time unit")
        ->capture_default_str();
    cmd->add_option("--res", o.res, "base mesh N x M cells (x = propagation, z = transverse)")
        ->capture_default_str();
    auto modal = [&](CLI::Option* opt, void (*copy)(ReplayParams&, const ReplayParams&)) {
        o.modal.emplace_back(opt, copy);
    };
    modal(cmd->add_option("--slices", o.params.slices,
                          "K slices (K - 1 more are inserted); default by --mode: 256, 256, 128")
              ->capture_default_str(),
          [](ReplayParams& p, const ReplayParams& d) { p.slices = d.slices; });
    cmd->add_option("--seed", o.params.seed, "noise seed")->capture_default_str();
    modal(cmd->add_option("--fluctuation,-F", o.params.fluctuation,
                          "F of eq. (5), 0..1; default by --mode: 0.3, 0.4, 0.4")
              ->capture_default_str(),
          [](ReplayParams& p, const ReplayParams& d) { p.fluctuation = d.fluctuation; });
    modal(cmd->add_option("--beta", o.params.noise.beta,
                          "noise spectral exponent; default by --mode: 2.0, 2.5, 2.5")
              ->capture_default_str(),
          [](ReplayParams& p, const ReplayParams& d) { p.noise.beta = d.noise.beta; });
    modal(cmd->add_option("--cutoff", o.params.noise.cutoff,
                          "noise filter cut-off c (wavenumbers); default by --mode: 128, 128, 64")
              ->capture_default_str(),
          [](ReplayParams& p, const ReplayParams& d) { p.noise.cutoff = d.noise.cutoff; });
    cmd->add_option("--filter", o.filter, "noise band kept: low, high or none")
        ->capture_default_str();
    cmd->add_option("--noise-time", o.params.noise.timeSamples, "T noise samples in time")
        ->capture_default_str();
    cmd->add_option("--time-unit", o.params.timeUnitSeconds,
                    "simulated seconds per animation time unit (A = this / frame time)")
        ->capture_default_str();
    cmd->add_option("--policy", o.policy, "frames outside the cache: clamp or loop")
        ->capture_default_str();
    cmd->add_option("--sigma", o.params.sigma, "Gaussian sigma of eq. (7), cells")
        ->capture_default_str();
    cmd->add_option("--fps", o.playbackFps, "output frames per simulated second")
        ->capture_default_str();
    cmd->add_option("--start", o.start, "simulated second of the first frame")
        ->capture_default_str();
    cmd->add_flag("--json", o.json, "print one JSON object on stdout");
}

/// Resolves the string options into o.params and validates everything.
void finishOptions(Options& o) {
    int n = 0, m = 0;
    char x = 0, extra = 0;
    if (std::sscanf(o.res.c_str(), "%d%c%d%c", &n, &x, &m, &extra) != 3 || (x != 'x' && x != 'X')) {
        throw std::invalid_argument(fmt::format("--res must look like 128x128, got '{}'", o.res));
    }
    o.params.cellsX = n;
    o.params.cellsZ = m;
    o.modeParams.mode = replayModeFromString(o.mode);
    const ReplayParams table4 = paperDefaults(o.modeParams.mode);
    for (const auto& [option, copy] : o.modal) {
        if (option->count() == 0)
            copy(o.params, table4); // not given: the mode's Table 4 value
    }
    o.params.policy = framePolicyFromString(o.policy);
    if (o.filter == "low") {
        o.params.noise.filter = NoiseFilter::LowPass;
    } else if (o.filter == "high") {
        o.params.noise.filter = NoiseFilter::HighPass;
    } else if (o.filter == "none") {
        o.params.noise.filter = NoiseFilter::None;
    } else {
        throw std::invalid_argument(
            fmt::format("--filter must be low, high or none, got '{}'", o.filter));
    }
    if (!(o.playbackFps > 0.0) || !std::isfinite(o.playbackFps)) {
        throw std::invalid_argument(fmt::format("--fps must be > 0, got {}", o.playbackFps));
    }
    if (!std::isfinite(o.start))
        throw std::invalid_argument("--start must be finite");
    o.params.validate();
    o.modeParams.validate();
}

/// Animation time of output frame i: simulated time / time unit (eq. 5's tau).
double tauOf(const Options& o, std::size_t i) {
    return (o.start + static_cast<double>(i) / o.playbackFps) / o.params.timeUnitSeconds;
}

/// The frames that `taus` select, decoded from the cache (no other frame is read).
FrameSet loadUsed(const cache::Reader& reader, std::span<const SliceSampler> samplers,
                  const std::vector<double>& taus) {
    FrameSet set;
    set.header = reader.header();
    set.frameCount = reader.frameCount();
    set.ids = framesUsed(samplers, taus);
    set.frames.reserve(set.ids.size());
    for (std::uint32_t id : set.ids)
        set.frames.push_back(reader.readFrame(id));
    return set;
}

/// Mean water depth of the held frames: mean surface height above the domain's bottom.
double waterDepth(const FrameSet& set) {
    double sum = 0.0;
    std::size_t count = 0;
    for (const cache::Frame& f : set.frames) {
        for (std::size_t p = 1; p < f.surface.size(); p += 2)
            sum += f.surface[p];
        count += f.surfaceCount();
    }
    const double bottom = set.header.domain.yMin;
    return count > 0 ? sum / static_cast<double>(count) - bottom
                     : static_cast<double>(set.header.domain.yMax) - bottom;
}

json paramsJson(const Options& o, const FrameSet& set, double A) {
    const ReplayParams& p = o.params;
    return {{"mode", o.mode},
            {"mode_params", toJson(o.modeParams)},
            {"cache", o.cache},
            {"params", toJson(p)},
            {"res", {p.cellsX, p.cellsZ}},
            {"slices", p.slices},
            {"slices_total", 2 * p.slices - 1},
            {"seed", p.seed},
            {"fluctuation", p.fluctuation},
            {"beta", p.noise.beta},
            {"cutoff", p.noise.cutoff},
            {"filter", o.filter},
            {"noise_time_samples", p.noise.timeSamples},
            {"sigma_cells", p.sigma},
            {"window_cells", {3, 2}},
            {"policy", o.policy},
            {"time_unit_seconds", p.timeUnitSeconds},
            {"A_frames_per_time_unit", A},
            {"playback_fps", o.playbackFps},
            {"start_seconds", o.start},
            {"frames_in_cache", set.frameCount},
            {"frames_decoded", set.ids.size()}};
}

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const auto hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

int runBench(Options& o, int frames, int warmup, int errorFrames, int cpuFrames) {
    finishOptions(o);
    if (frames < 1)
        throw std::invalid_argument("--frames must be >= 1");
    const cache::Reader reader(o.cache);
    const double A = framesPerTimeUnit(reader.header(), o.params);
    const std::vector<SliceSampler> samplers =
        makeSamplers(o.params, o.modeParams, reader.frameCount(), A);

    std::vector<double> taus(static_cast<std::size_t>(warmup + frames));
    for (std::size_t i = 0; i < taus.size(); ++i)
        taus[i] = tauOf(o, i);
    auto t0 = Clock::now();
    const FrameSet set = loadUsed(reader, samplers, taus);
    const double decodeMs = msSince(t0);

    const EglContext context;
    t0 = Clock::now();
    ModeReplay gpu(set, o.params, o.modeParams, samplers);
    const double uploadMs = msSince(t0);

    for (int i = 0; i < warmup; ++i) {
        gpu.update(taus[static_cast<std::size_t>(i)]);
        gpu.finish();
    }
    // Synced frames: each one waits for the GPU (glFinish) before the clock stops.
    std::vector<double> frameMs(static_cast<std::size_t>(frames));
    const auto all0 = Clock::now();
    for (int i = 0; i < frames; ++i) {
        const auto f0 = Clock::now();
        gpu.update(taus[static_cast<std::size_t>(warmup + i)]);
        gpu.finish();
        frameMs[static_cast<std::size_t>(i)] = msSince(f0);
    }
    const double totalMs = msSince(all0);

    // Per-stage GPU times from timer queries, in a separate run (queries cost a little).
    const int timed = std::min(frames, 200);
    double lookupMs = 0.0, reconstructMs = 0.0, synthesisMs = 0.0, spiralMs = 0.0;
    gpu.setTiming(true);
    for (int i = 0; i < timed; ++i) {
        gpu.update(taus[static_cast<std::size_t>(warmup + i)]);
        const ModeStageTimes st = gpu.stageTimes();
        lookupMs += st.sliceLookupMs;
        reconstructMs += st.reconstructMs;
        synthesisMs += st.synthesisMs;
        spiralMs += st.spiralMs;
    }
    gpu.setTiming(false);

    // Error against the double-precision CPU reference on evenly spread frames.
    const CpuModeReference cpu(set, o.params, o.modeParams, samplers);
    double maxAbs = 0.0, sumSq = 0.0;
    std::size_t cells = 0;
    bool framesExact = true;
    const int errorCount = std::min(errorFrames, frames);
    for (int e = 0; e < errorCount; ++e) {
        const double tau = taus[static_cast<std::size_t>(warmup + (e * frames) / errorCount)];
        gpu.update(tau);
        const auto sliceFrames = gpu.readSliceFrames();
        for (std::size_t d = 0; d < samplers.size(); ++d)
            framesExact = framesExact && sliceFrames[d] == samplers[d].frames(tau);
        const HeightField g = gpu.readHeights();
        const HeightField r = cpu.heights(tau);
        for (std::size_t i = 0; i < g.heights.size(); ++i) {
            const double d = std::isfinite(g.heights[i]) ? std::abs(g.heights[i] - r.heights[i])
                                                         : std::numeric_limits<double>::infinity();
            maxAbs = std::max(maxAbs, d);
            sumSq += d * d;
        }
        cells += g.heights.size();
    }
    const double rms = cells > 0 ? std::sqrt(sumSq / static_cast<double>(cells)) : 0.0;
    const double depth = waterDepth(set);

    // The CPU reference's own speed, for comparison.
    double cpuMs = 0.0;
    const int cpuCount = std::min(cpuFrames, frames);
    if (cpuCount > 0) {
        t0 = Clock::now();
        for (int i = 0; i < cpuCount; ++i)
            (void)cpu.heights(taus[static_cast<std::size_t>(warmup + i)]);
        cpuMs = msSince(t0) / cpuCount;
    }

    const double meanMs = totalMs / frames;
    json out = paramsJson(o, set, A);
    out.update({{"renderer", context.renderer()},
                {"gl_version", context.version()},
                {"egl_platform", context.platform()},
                {"frames", frames},
                {"warmup", warmup},
                {"synced", true},
                {"fps", 1000.0 / meanMs},
                {"frame_ms_mean", meanMs},
                {"frame_ms_median", percentile(frameMs, 0.5)},
                {"frame_ms_p95", percentile(frameMs, 0.95)},
                {"stage_gpu_ms",
                 {{"slice_lookup", lookupMs / timed},
                  {"reconstruct", reconstructMs / timed},
                  {"synthesis", synthesisMs / timed},
                  {"spiral_mapping", spiralMs / timed},
                  {"column_pass_once", gpu.columnPassMs()}}},
                {"slice_sets", samplers.size()},
                {"timed_frames", timed},
                {"decode_ms", decodeMs},
                {"upload_ms", uploadMs},
                {"uploaded_bytes", gpu.uploadedBytes()},
                {"error_frames", errorCount},
                {"frames_exact", framesExact},
                {"max_abs_error", maxAbs},
                {"rms_error", rms},
                {"water_depth", depth},
                {"max_rel_error", maxAbs / depth},
                {"cpu_reference_frames", cpuCount},
                {"cpu_reference_ms", cpuMs},
                {"cpu_reference_fps", cpuMs > 0.0 ? 1000.0 / cpuMs : 0.0}});
    if (o.json) {
        std::cout << out.dump() << "\n";
    } else {
        std::cout << fmt::format(
            "swell-play bench  {}  ({}, EGL {})\n"
            "  mode {}, {}x{} cells, K = {} ({} slices), seed {}, F {}, {} of {} cache frames "
            "decoded\n"
            "  {:.1f} fps synced over {} frames: median {:.3f} ms, p95 {:.3f} ms\n"
            "  GPU stages: slice lookup {:.4f} ms, reconstruct {:.4f} ms, synthesis {:.4f} ms, "
            "spiral mapping {:.4f} ms; column pass once {:.2f} ms\n"
            "  error vs CPU reference ({} frames): max {:.3g} m, rms {:.3g} m, max {:.3g} of depth "
            "{:.3g} m; frame choice {}\n"
            "  CPU reference: {:.1f} fps ({:.2f} ms/frame)\n",
            context.renderer(), context.version(), context.platform(), o.mode, o.params.cellsX,
            o.params.cellsZ, o.params.slices, 2 * o.params.slices - 1, o.params.seed,
            o.params.fluctuation, set.ids.size(), set.frameCount, 1000.0 / meanMs, frames,
            percentile(frameMs, 0.5), percentile(frameMs, 0.95), lookupMs / timed,
            reconstructMs / timed, synthesisMs / timed, spiralMs / timed, gpu.columnPassMs(),
            errorCount, maxAbs, rms, maxAbs / depth, depth, framesExact ? "exact" : "DIFFERS",
            cpuMs > 0 ? 1000.0 / cpuMs : 0.0, cpuMs);
    }
    if (!framesExact || !(maxAbs <= 1e-4 * depth)) {
        std::cerr
            << "swell-play: GPU result differs from the CPU reference beyond 1e-4 of the depth\n";
        return 2;
    }
    return 0;
}

int runHeights(Options& o, const std::string& outDir, double seconds) {
    finishOptions(o);
    if (!(seconds > 0.0) || !std::isfinite(seconds)) {
        throw std::invalid_argument(fmt::format("--seconds must be > 0, got {}", seconds));
    }
    const cache::Reader reader(o.cache);
    const double A = framesPerTimeUnit(reader.header(), o.params);
    const std::vector<SliceSampler> samplers =
        makeSamplers(o.params, o.modeParams, reader.frameCount(), A);
    const auto count = static_cast<std::size_t>(std::max(1.0, std::round(seconds * o.playbackFps)));
    std::vector<double> taus(count);
    for (std::size_t i = 0; i < count; ++i)
        taus[i] = tauOf(o, i);
    const FrameSet set = loadUsed(reader, samplers, taus);

    std::filesystem::create_directories(outDir);
    const EglContext context;
    ModeReplay gpu(set, o.params, o.modeParams, samplers);
    const cache::Domain& d = set.header.domain;
    const HeightScale scale{d.yMin, (static_cast<double>(d.yMax) - d.yMin) / 65535.0};
    json frames = json::array();
    const bool progress = ::isatty(2) != 0 && !o.json;
    const auto t0 = Clock::now();
    for (std::size_t i = 0; i < count; ++i) {
        gpu.update(taus[i]);
        const std::string name = fmt::format("height_{:05d}.png", i);
        writeHeightPng(std::filesystem::path(outDir) / name, gpu.readHeights(), scale);
        frames.push_back({{"file", name},
                          {"tau", taus[i]},
                          {"seconds", o.start + static_cast<double>(i) / o.playbackFps}});
        if (progress) {
            const double eta = msSince(t0) / 1000.0 * static_cast<double>(count - i - 1) /
                               static_cast<double>(i + 1);
            std::cerr << fmt::format("\rswell-play heights: {}/{} frames, ETA {:.0f} s ", i + 1,
                                     count, eta);
        }
    }
    if (progress)
        std::cerr << "\n";
    json meta = paramsJson(o, set, A);
    meta.update({{"renderer", context.renderer()},
                 {"format", "16-bit greyscale PNG; height_m = offset + value * scale"},
                 {"scale", {{"offset", scale.offset}, {"scale", scale.scale}, {"units", "m"}}},
                 {"layout", "column n = x cell (x = x0 + (n + 0.5) dx), row m = z cell"},
                 {"x0", gpu.grid().x0},
                 {"dx", gpu.grid().dx},
                 {"dz", gpu.grid().dz},
                 {"count", count},
                 {"frames", frames}});
    const auto metaPath = std::filesystem::path(outDir) / "heights.json";
    std::ofstream(metaPath) << meta.dump(2) << "\n";
    if (o.json) {
        std::cout << json{{"out", outDir},
                          {"count", count},
                          {"frames_decoded", set.ids.size()},
                          {"renderer", context.renderer()},
                          {"mode", o.mode},
                          {"seed", o.params.seed}}
                         .dump()
                  << "\n";
    } else {
        std::cout << fmt::format("swell-play heights: {} frames ({}x{}) in {}, metadata {} ({})\n",
                                 count, o.params.cellsX, o.params.cellsZ, outDir, metaPath.string(),
                                 context.renderer());
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"swell-play: headless replay of a .swell cache (stochastic slices, eq. 5-7)"};
    app.require_subcommand(1);

    Options bench;
    int frames = 1000, warmup = 50, errorFrames = 8, cpuFrames = 3;
    auto* benchCmd =
        app.add_subcommand("bench", "time the GPU replay and check it against the CPU reference");
    addCommon(benchCmd, bench);
    benchCmd->add_option("--frames", frames, "timed frames")
        ->capture_default_str()
        ->check(CLI::Range(1, 10000000));
    benchCmd->add_option("--warmup", warmup, "untimed frames first")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000000));
    benchCmd->add_option("--error-frames", errorFrames, "frames compared with the CPU reference")
        ->capture_default_str()
        ->check(CLI::Range(0, 100000));
    benchCmd->add_option("--cpu-frames", cpuFrames, "frames timed on the CPU reference (0: skip)")
        ->capture_default_str()
        ->check(CLI::Range(0, 100000));

    Options heights;
    std::string outDir;
    double seconds = 2.0;
    auto* heightsCmd = app.add_subcommand("heights", "write height fields (16-bit PNG + JSON)");
    addCommon(heightsCmd, heights);
    heightsCmd->add_option("--out", outDir, "output folder")->required();
    heightsCmd->add_option("--seconds", seconds, "simulated seconds to write")
        ->capture_default_str();

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "swell-play: " << e.what() << " (see --help)\n";
        return e.get_exit_code() != 0 ? e.get_exit_code() : 1;
    }
    try {
        if (*benchCmd)
            return runBench(bench, frames, warmup, errorFrames, cpuFrames);
        return runHeights(heights, outDir, seconds);
    } catch (const cache::CacheError& e) {
        std::cerr << "swell-play: " << e.what() << "\n";
    } catch (const RuntimeError& e) {
        std::cerr << "swell-play: " << e.what() << "\n";
    } catch (const std::invalid_argument& e) {
        std::cerr << "swell-play: " << e.what() << "\n";
    } catch (const std::exception& e) {
        std::cerr << "swell-play: " << e.what() << "\n";
    }
    return 1;
}
