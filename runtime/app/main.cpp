// swell-play: headless replay of a .swell cache (paper Sec. 4): bench, height fields and shaded
// renders (Sec. 5).
// The library does the work; this file parses options, reads the cache, times and prints.

#include "swell/cache/error.h"
#include "swell/cache/reader.h"
#include "swell/runtime/replay/cpu_reconstruction.h"
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/error.h"
#include "swell/runtime/io/exporters.h"
#include "swell/runtime/replay/fidelity.h"
#include "swell/runtime/replay/gpu_replay.h"
#include "swell/runtime/io/height_png.h"
#include "swell/runtime/modes/mode_replay.h"
#include "swell/runtime/modes/mode_splashes.h"
#include "swell/runtime/replay/slice_sampler.h"
#include "swell/runtime/render/splash_system.h"
#include "swell/runtime/render/water_renderer.h"

#include "fidelity.h"
#include "play_common.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace {

using namespace swell;
using namespace swell::runtime;
using namespace swell::play;

int runBench(Options& o, int frames, int warmup, int errorFrames, int cpuFrames,
             const std::string& referenceCache) {
    finishOptions(o);
    if (frames < 1)
        throw std::invalid_argument("--frames must be >= 1");
    const cache::Reader reader(o.cache);
    resolveAutoRes(o, reader.header());
    std::vector<double> taus(static_cast<std::size_t>(warmup + frames));
    for (std::size_t i = 0; i < taus.size(); ++i)
        taus[i] = tauOf(o, i);
    auto t0 = Clock::now();
    const ReplaySetup setup = prepareReplay(o, reader, taus);
    const double decodeMs = msSince(t0);
    const FrameSet& set = setup.set;
    const std::vector<SliceSampler>& samplers = setup.samplers;

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
    StageTimes sum;
    gpu.setTiming(true);
    for (int i = 0; i < timed; ++i) {
        gpu.update(taus[static_cast<std::size_t>(warmup + i)]);
        sum += gpu.stageTimes();
    }
    gpu.setTiming(false);
    const StageTimes stage = sum.mean(timed);

    // Error against the double-precision CPU reference on evenly spread frames; with
    // --reference-cache the reference reads the same frames from that cache (e.g. the float32
    // original of a quantized cache), so the error includes the encoding's.
    std::optional<FrameSet> refSet;
    if (!referenceCache.empty()) {
        const cache::Reader refReader(referenceCache);
        if (refReader.frameCount() != reader.frameCount()) {
            throw std::invalid_argument(fmt::format(
                "--reference-cache {} has {} frames, {} has {}", referenceCache,
                refReader.frameCount(), o.cache, reader.frameCount()));
        }
        refSet = loadUsed(refReader, samplers, taus);
    }
    const CpuModeReference cpu(refSet ? *refSet : set, o.params, o.modeParams, samplers);
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
    json out = paramsJson(o, setup);
    out.update({{"renderer", context.renderer()},
                {"llvmpipe_threads", context.llvmpipeThreads()},
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
                 {{"slice_lookup", stage.sliceLookupMs},
                  {"reconstruct", stage.reconstructMs},
                  {"synthesis", stage.synthesisMs},
                  {"spiral_mapping", stage.spiralMs},
                  {"column_pass_once", gpu.columnPassMs()}}},
                {"slice_sets", samplers.size()},
                {"timed_frames", timed},
                {"decode_ms", decodeMs},
                {"timeline_search_ms", setup.plan.searchMs},
                {"upload_ms", uploadMs},
                {"uploaded_bytes", gpu.uploadedBytes()},
                {"error_frames", errorCount},
                {"frames_exact", framesExact},
                {"max_abs_error", maxAbs},
                {"rms_error", rms},
                {"water_depth", depth},
                {"max_rel_error", maxAbs / depth},
                {"reference_cache", referenceCache},
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
            percentile(frameMs, 0.5), percentile(frameMs, 0.95), stage.sliceLookupMs,
            stage.reconstructMs, stage.synthesisMs, stage.spiralMs, gpu.columnPassMs(),
            errorCount, maxAbs, rms, maxAbs / depth, depth, framesExact ? "exact" : "DIFFERS",
            cpuMs > 0 ? 1000.0 / cpuMs : 0.0, cpuMs);
    }
    if (!referenceCache.empty()) // the encodings differ: report the error, judge nothing
        return framesExact && std::isfinite(maxAbs) ? 0 : 2;
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
    resolveAutoRes(o, reader.header());
    const std::vector<double> taus = outputTaus(o, seconds);
    const std::size_t count = taus.size();
    const ReplaySetup setup = prepareReplay(o, reader, taus);
    const FrameSet& set = setup.set;
    const std::vector<SliceSampler>& samplers = setup.samplers;

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
    json meta = paramsJson(o, setup);
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

// ---- render (Sec. 5) -------------------------------------------------------------------

/// Options of `swell-play render` beyond the shared ones.
struct RenderOptions {
    std::string outDir;            ///< output folder
    std::string size = "1280x720"; ///< image width x height
    double seconds = 3.0;          ///< simulated seconds to render
    std::string video;             ///< mp4 to encode with ffmpeg (empty: none)
    std::string exports;           ///< comma list: heights, mesh, splashes
    std::string skyDir;            ///< folder with px, nx, py, ny, pz, nz .png (empty: procedural)
    std::vector<double> eye;       ///< camera position x y z (empty: default framing)
    std::vector<double> target;    ///< camera target x y z (empty: default framing)
    double fov = 40.0;             ///< vertical field of view, degrees
    int sheetFrames = 6;           ///< frames on the contact sheet
    int pngCompression = 1;        ///< zlib level of the frame PNGs
    bool noSplashes = false;       ///< skip the splash pass
    ShadingParams shading;         ///< shading (size and samples are set from the options)
    SplashParams splash;           ///< splash particles (Sec. 5)
    SkyParams sky;                 ///< procedural sky and sun
};

/// The executable `name` on PATH, or empty.
std::string findOnPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    if (path == nullptr)
        return {};
    std::string dirs(path);
    std::size_t start = 0;
    while (start <= dirs.size()) {
        const std::size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::filesystem::path candidate =
            std::filesystem::path(end > start ? dirs.substr(start, end - start) : ".") / name;
        if (::access(candidate.c_str(), X_OK) == 0)
            return candidate.string();
        start = end + 1;
    }
    return {};
}

/// Runs argv[0] with arguments (no shell), waits; returns its exit status (-1: not run).
int runProcess(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (const std::string& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawn(&pid, args[0].c_str(), nullptr, nullptr, argv.data(), environ) != 0)
        return -1;
    int status = 0;
    if (waitpid(pid, &status, 0) < 0)
        return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

Vec3 toVec3(const std::vector<double>& v, const char* what) {
    if (v.size() != 3)
        throw std::invalid_argument(fmt::format("{} needs three numbers x y z", what));
    return {v[0], v[1], v[2]};
}

json vec3Json(const Vec3& v) {
    return json::array({v[0], v[1], v[2]});
}

int runRender(Options& o, RenderOptions& r) {
    finishOptions(o);
    int width = 0, height = 0;
    char x = 0, extra = 0;
    if (std::sscanf(r.size.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 ||
        (x != 'x' && x != 'X')) {
        throw std::invalid_argument(
            fmt::format("--size must look like 1280x720, got '{}'", r.size));
    }
    r.shading.width = width;
    r.shading.height = height;
    r.shading.validate();
    r.splash.enabled = !r.noSplashes;
    r.splash.validate();
    r.sky.validate();
    if (!(r.seconds > 0.0) || !std::isfinite(r.seconds)) {
        throw std::invalid_argument(fmt::format("--seconds must be > 0, got {}", r.seconds));
    }
    bool exportHeights = false, exportMesh = false, exportSplashes = false;
    for (std::size_t start = 0; start < r.exports.size();) {
        const std::size_t end = std::min(r.exports.find(',', start), r.exports.size());
        const std::string item = r.exports.substr(start, end - start);
        if (item == "heights") {
            exportHeights = true;
        } else if (item == "mesh") {
            exportMesh = true;
        } else if (item == "splashes") {
            exportSplashes = true;
        } else if (!item.empty()) {
            throw std::invalid_argument(
                fmt::format("--export takes heights, mesh, splashes; got '{}'", item));
        }
        start = end + 1;
    }
    if (r.eye.empty() != r.target.empty())
        throw std::invalid_argument("--camera and --target go together");
    if (!r.video.empty() && r.video.find(".mp4") == std::string::npos) {
        throw std::invalid_argument(
            fmt::format("--video must name an .mp4 file, got '{}'", r.video));
    }

    const cache::Reader reader(o.cache);
    resolveAutoRes(o, reader.header());
    const std::vector<double> taus = outputTaus(o, r.seconds);
    const std::size_t count = taus.size();
    const ReplaySetup setup = prepareReplay(o, reader, taus);
    const FrameSet& set = setup.set;
    const std::vector<SliceSampler>& samplers = setup.samplers;
    const CubeFaces faces = r.skyDir.empty() ? proceduralSky(r.sky) : loadSkyImages(r.skyDir);

    const std::filesystem::path out(r.outDir);
    std::filesystem::create_directories(out);
    if (exportHeights)
        std::filesystem::create_directories(out / "heights");
    if (exportMesh)
        std::filesystem::create_directories(out / "mesh");
    if (exportSplashes)
        std::filesystem::create_directories(out / "splashes");

    const EglContext context;
    ModeReplay gpu(set, o.params, o.modeParams, samplers);
    const Grid& grid = gpu.grid();
    const cache::Domain& domain = set.header.domain;
    const double waterLevel = domain.yMin + waterDepth(set);
    // The whirlpool's spirals show best from higher up; the surging and ripple waves from a
    // lower three-quarter view.
    const double elevation = o.modeParams.mode == ReplayMode::Whirlpool ? 55.0 : 28.0;
    Camera camera = defaultCamera(grid, domain, waterLevel, static_cast<double>(width) / height,
                                  r.fov, elevation);
    if (!r.eye.empty()) {
        camera.position = toVec3(r.eye, "--camera");
        camera.target = toVec3(r.target, "--target");
    }
    camera.validate();
    WaterRenderer renderer(grid, domain, r.shading, faces, sunDirection(r.sky));
    // The artificial splashes get their own stream, derived from the run's seed.
    // Each slice set (the ripple's directions) has its own; they follow the mode's layout
    // (mode_splashes.h).
    std::vector<SplashSystem> splashSets;
    splashSets.reserve(samplers.size());
    for (int d = 0; d < static_cast<int>(samplers.size()); ++d)
        splashSets.emplace_back(set, grid, r.splash,
                                sliceSetSeed(o.params.seed, d) ^ 0x5b1a54e5ULL);
    const SplashSystem& splashes = splashSets.front();
    // Stage times (GL timestamp queries) on every 8th frame; the frame rate is taken over the
    // other frames, so the queries do not slow what is measured.
    constexpr std::size_t kTimedEvery = 8;

    const cache::Domain& d = domain;
    const HeightScale scale{d.yMin, (static_cast<double>(d.yMax) - d.yMin) / 65535.0};
    // Contact sheet: sheetFrames frames evenly spread, each downscaled to about 320 px wide.
    const std::size_t sheetCount =
        std::min<std::size_t>(static_cast<std::size_t>(std::max(r.sheetFrames, 1)), count);
    const int sheetFactor = std::max(1, width / 320);
    std::vector<Image> sheet;
    json frames = json::array();
    double drawMs = 0.0, spriteMs = 0.0, readMs = 0.0, writeMs = 0.0, exportMs = 0.0;
    double timedDrawMs = 0.0, drawCpuMs = 0.0;
    std::size_t timedFrames = 0;
    StageTimes stages; // replay and render passes of the timed frames, summed
    std::size_t spriteTotal = 0, culledTotal = 0;
    const bool progress = ::isatty(2) != 0 && !o.json;
    const auto t0 = Clock::now();
    for (std::size_t i = 0; i < count; ++i) {
        const double seconds = o.start + static_cast<double>(i) / o.playbackFps;
        const bool timed =
            i % kTimedEvery == kTimedEvery / 2 || count <= kTimedEvery / 2; // not frame 0 (set-up)
        gpu.setTiming(timed);
        renderer.setTiming(timed);
        auto ts = Clock::now();
        const double cpu0 = processCpuMs();
        gpu.update(taus[i]);
        renderer.drawSurface(gpu.heightBuffer(), camera, splashes.active());
        // While the rasteriser draws the surface: the splash sprites. Each real slice shows its
        // own frame's splashes, the same frame choice as the GPU (eq. 5).
        const auto spritesStart = Clock::now();
        std::vector<SplashSprite> sprites;
        for (std::size_t d = 0; d < splashSets.size() && splashes.active(); ++d) {
            std::vector<SplashSprite> more =
                splashSets[d].sprites(samplers[d].frames(taus[i]), seconds);
            placeSplashes(more, grid, o.modeParams, static_cast<int>(d), taus[i]);
            sprites.insert(sprites.end(), more.begin(), more.end());
        }
        spriteMs += msSince(spritesStart);
        spriteTotal += sprites.size();
        renderer.drawSplashes(sprites, r.splash.spriteRadius);
        gpu.finish();
        const double frameDrawMs = msSince(ts);
        const double frameCpuMs = processCpuMs() - cpu0;
        culledTotal += renderer.lastCulledSplashCount();
        if (timed) {
            ++timedFrames;
            timedDrawMs += frameDrawMs;
            stages += gpu.stageTimes();
            stages += renderer.stageTimes();
        } else {
            drawMs += frameDrawMs;
            drawCpuMs += frameCpuMs;
        }

        ts = Clock::now();
        const Image image = renderer.readPixels();
        readMs += msSince(ts);
        ts = Clock::now();
        const std::string name = fmt::format("frame_{:05d}.png", i);
        writePng(out / name, image, r.pngCompression);
        if (sheet.size() < sheetCount &&
            i == sheet.size() * (count - 1) / std::max<std::size_t>(sheetCount - 1, 1)) {
            sheet.push_back(downscale(image, sheetFactor));
        }
        writeMs += msSince(ts);

        ts = Clock::now();
        json entry{{"file", name},
                   {"tau", taus[i]},
                   {"seconds", seconds},
                   {"splash_sprites", sprites.size()},
                   {"splash_sprites_culled", renderer.lastCulledSplashCount()}};
        {
            const HeightField field = gpu.readHeights();
            // How much wave the frame shows (tools/check_demo holds the demo to it).
            entry["height_spread_m"] = fieldSpread(field);
            entry["flat_rows"] = flatRows(field);
            if (exportHeights) {
                const std::string h = fmt::format("heights/height_{:05d}.png", i);
                writeHeightPng(out / h, field, scale);
                entry["heights"] = h;
            }
            if (exportMesh) {
                const std::string m = fmt::format("mesh/surface_{:05d}.ply", i);
                writeSurfacePly(out / m, makeSurfaceMesh(field, grid),
                                fmt::format("swell-play surface, frame {}, t = {} s", i, seconds));
                entry["mesh"] = m;
            }
        }
        if (exportSplashes) {
            const std::string sp = fmt::format("splashes/splashes_{:05d}.ply", i);
            writeSplashPly(out / sp, sprites,
                           fmt::format("swell-play splashes, frame {}, t = {} s", i, seconds));
            entry["splashes"] = sp;
        }
        exportMs += msSince(ts);
        frames.push_back(entry);
        if (progress) {
            const double eta = msSince(t0) / 1000.0 * static_cast<double>(count - i - 1) /
                               static_cast<double>(i + 1);
            std::cerr << fmt::format("\rswell-play render: {}/{} frames, ETA {:.0f} s ", i + 1,
                                     count, eta);
        }
    }
    if (progress)
        std::cerr << "\n";
    const double totalMs = msSince(t0);
    const Image sheetImage = contactSheet(sheet, 3);
    writePng(out / "contact_sheet.png", sheetImage, 6);

    // Video through ffmpeg when it is installed; PNGs only (and a clear message) when not.
    std::string videoStatus = "not requested";
    if (!r.video.empty()) {
        const std::string ffmpeg = findOnPath("ffmpeg");
        if (ffmpeg.empty()) {
            videoStatus = "skipped: ffmpeg not found";
            std::cerr << "swell-play: ffmpeg not found on PATH: wrote the PNG frames only (install "
                         "ffmpeg for --video)\n";
        } else {
            const std::filesystem::path videoPath(r.video);
            if (videoPath.has_parent_path())
                std::filesystem::create_directories(videoPath.parent_path());
            const int rc = runProcess(
                {ffmpeg, "-y", "-loglevel", "error", "-framerate", fmt::format("{}", o.playbackFps),
                 "-i", (out / "frame_%05d.png").string(), "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                 "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "20", r.video});
            if (rc != 0)
                throw RuntimeError(fmt::format("ffmpeg failed (exit {}) writing {}", rc, r.video));
            videoStatus = "written";
        }
    }

    const double n = static_cast<double>(count);
    const double nt = static_cast<double>(timedFrames);
    // Frames without queries give the frame rate; a render shorter than kTimedEvery + 1 frames
    // has only the first frame timed apart from them (its first draw includes shader set-up).
    const double untimed = n - nt;
    const double drawMsPerFrame = untimed > 0 ? drawMs / untimed : timedDrawMs / nt;
    json meta = paramsJson(o, setup);
    meta.update({{"renderer", context.renderer()},
                 {"llvmpipe_threads", context.llvmpipeThreads()},
                 {"gl_version", context.version()},
                 {"egl_platform", context.platform()},
                 {"size", {width, height}},
                 {"samples", renderer.samples()},
                 {"seconds", r.seconds},
                 {"count", count},
                 {"camera",
                  {{"position", vec3Json(camera.position)},
                   {"target", vec3Json(camera.target)},
                   {"fov_y_degrees", camera.fovYDegrees},
                   {"near", camera.nearPlane},
                   {"far", camera.farPlane}}},
                 {"sky",
                  {{"source", r.skyDir.empty() ? std::string("procedural") : r.skyDir},
                   {"sun_azimuth_degrees", r.sky.sunAzimuthDegrees},
                   {"sun_elevation_degrees", r.sky.sunElevationDegrees},
                   {"cloud_cover", r.sky.cloudCover},
                   {"face_size", faces[0].width}}},
                 {"shading",
                  {{"refractive_index", r.shading.refractiveIndex},
                   {"absorption_per_m", vec3Json(r.shading.absorption)},
                   {"scatter_colour", vec3Json(r.shading.scatterColour)},
                   {"bed_colour", vec3Json(r.shading.bedColour)},
                   {"sun_shininess", r.shading.sunShininess},
                   {"sun_intensity", r.shading.sunIntensity},
                   {"sides", r.shading.sides}}},
                 {"splash",
                  {{"active", splashes.active()},
                   {"artificial_per_real", r.splash.artificialPerReal},
                   {"spawn_radius_m", r.splash.spawnRadius},
                   {"sprite_radius_m", r.splash.spriteRadius},
                   {"velocity_jitter", r.splash.velocityJitter},
                   {"lifetime_s", {r.splash.minLifetime, r.splash.maxLifetime}},
                   {"gravity", r.splash.gravity},
                   {"seed", o.params.seed ^ 0x5b1a54e5ULL},
                   {"sprites_mean", static_cast<double>(spriteTotal) / n},
                   {"culled_under_water_mean", static_cast<double>(culledTotal) / n}}},
                 {"exports",
                  {{"heights", exportHeights}, {"mesh", exportMesh}, {"splashes", exportSplashes}}},
                 {"height_scale",
                  {{"offset", scale.offset},
                   {"scale", scale.scale},
                   {"units", "m"},
                   {"format", "16-bit greyscale PNG; height_m = offset + value * scale; "
                              "column n = x cell (x = x0 + (n + 0.5) dx), row m = z cell"}}},
                 {"x0", grid.x0},
                 {"dx", grid.dx},
                 {"dz", grid.dz},
                 {"video", r.video},
                 {"video_status", videoStatus},
                 {"contact_sheet", "contact_sheet.png"},
                 {"shaded_fps", 1000.0 / drawMsPerFrame},
                 {"shaded_fps_frames", untimed > 0 ? untimed : nt},
                 {"timing_ms_per_frame",
                  {{"draw_synced", drawMsPerFrame},
                   {"draw_cpu", untimed > 0 ? drawCpuMs / untimed : 0.0},
                   {"splash_sprites_cpu", spriteMs / n},
                   {"readback", readMs / n},
                   {"png_write", writeMs / n},
                   {"exports", exportMs / n},
                   {"total", totalMs / n}}},
                 {"stage_gpu_ms",
                  {{"slice_lookup", stages.sliceLookupMs / nt},
                   {"reconstruct", stages.reconstructMs / nt},
                   {"sky", stages.skyMs / nt},
                   {"water", stages.waterMs / nt},
                   {"splashes", stages.splashMs / nt},
                   {"resolve", stages.resolveMs / nt},
                   {"timed_frames", timedFrames}}},
                 {"frames", frames}});
    std::ofstream(out / "render.json") << meta.dump(2) << "\n";
    if (exportHeights) {
        // The sidecar `swell-play heights` writes, so tools read either folder the same way.
        json heightFrames = json::array();
        for (const json& f : frames) {
            heightFrames.push_back(
                {{"file",
                  std::filesystem::path(f["heights"].get<std::string>()).filename().string()},
                 {"tau", f["tau"]},
                 {"seconds", f["seconds"]}});
        }
        json heightsMeta = paramsJson(o, setup);
        heightsMeta.update(
            {{"renderer", context.renderer()},
             {"format", "16-bit greyscale PNG; height_m = offset + value * scale"},
             {"scale", {{"offset", scale.offset}, {"scale", scale.scale}, {"units", "m"}}},
             {"layout", "column n = x cell (x = x0 + (n + 0.5) dx), row m = z cell"},
             {"x0", grid.x0},
             {"dx", grid.dx},
             {"dz", grid.dz},
             {"count", count},
             {"frames", heightFrames}});
        std::ofstream(out / "heights" / "heights.json") << heightsMeta.dump(2) << "\n";
    }
    if (o.json) {
        json summary = meta;
        summary.erase("frames");
        summary["out"] = r.outDir;
        std::cout << summary.dump() << "\n";
    } else {
        std::cout << fmt::format(
            "swell-play render: {} frames {}x{} ({} samples) in {}, contact sheet {}\n"
            "  {}  ({}, EGL {})\n"
            "  shaded {:.1f} fps (replay + sprites + draw, synced; {:.0f} splash sprites per "
            "frame), {:.1f} frames/s with readback and PNG writing\n"
            "  GPU ms/frame: slice lookup {:.3f}, reconstruct {:.3f}, sky {:.3f}, water {:.3f}, "
            "splashes {:.3f}, resolve {:.3f}; CPU ms/frame: sprites {:.2f}, readback {:.2f}, PNG "
            "{:.2f}\n"
            "  video: {}\n",
            count, width, height, renderer.samples(), r.outDir,
            (out / "contact_sheet.png").string(), context.renderer(), context.version(),
            context.platform(), 1000.0 / drawMsPerFrame, static_cast<double>(spriteTotal) / n,
            1000.0 * n / totalMs, stages.sliceLookupMs / nt, stages.reconstructMs / nt, stages.skyMs / nt,
            stages.waterMs / nt, stages.splashMs / nt, stages.resolveMs / nt, spriteMs / n,
            readMs / n, writeMs / n,
            r.video.empty() ? videoStatus : r.video + " (" + videoStatus + ")");
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
    std::string referenceCache;
    benchCmd->add_option("--reference-cache", referenceCache,
                         "CPU reference reads its frames from this cache (same frame count), e.g. "
                         "the float32 original of a quantized cache; the error is then reported, "
                         "not judged");

    Options heights;
    std::string outDir;
    double seconds = 2.0;
    auto* heightsCmd = app.add_subcommand("heights", "write height fields (16-bit PNG + JSON)");
    addCommon(heightsCmd, heights);
    heightsCmd->add_option("--out", outDir, "output folder")->required();
    heightsCmd->add_option("--seconds", seconds, "simulated seconds to write")
        ->capture_default_str();

    Options render;
    RenderOptions renderOpts;
    auto* renderCmd = app.add_subcommand(
        "render", "shaded frames (PNG), contact sheet, optional mp4 and exports (Sec. 5)");
    addCommon(renderCmd, render);
    renderCmd->add_option("--out", renderOpts.outDir, "output folder")->required();
    renderCmd->add_option("--size", renderOpts.size, "image width x height")->capture_default_str();
    renderCmd->add_option("--seconds", renderOpts.seconds, "simulated seconds to render")
        ->capture_default_str();
    renderCmd->add_option("--video", renderOpts.video,
                          "also encode FILE.mp4 with ffmpeg (when installed)");
    renderCmd->add_option("--export", renderOpts.exports,
                          "per-frame exports, comma list of: heights (16-bit PNG + JSON), mesh "
                          "(PLY), splashes (PLY)");
    renderCmd->add_option("--samples", renderOpts.shading.samples, "multisampling (1: off)")
        ->capture_default_str();
    renderCmd
        ->add_option("--camera", renderOpts.eye,
                     "camera position x y z (metres; default: framing of the domain)")
        ->expected(3);
    renderCmd->add_option("--target", renderOpts.target, "camera target x y z (metres)")
        ->expected(3);
    renderCmd->add_option("--fov", renderOpts.fov, "vertical field of view, degrees")
        ->capture_default_str();
    renderCmd->add_option(
        "--sky", renderOpts.skyDir,
        "folder of six sky images px nx py ny pz nz .png (default: procedural sky)");
    renderCmd
        ->add_option("--sun-azimuth", renderOpts.sky.sunAzimuthDegrees,
                     "sun azimuth, degrees (0 = +x, 90 = +z)")
        ->capture_default_str();
    renderCmd
        ->add_option("--sun-elevation", renderOpts.sky.sunElevationDegrees,
                     "sun elevation, degrees")
        ->capture_default_str();
    renderCmd
        ->add_option("--splash-count", renderOpts.splash.artificialPerReal,
                     "artificial splashes around each real one (Sec. 5)")
        ->capture_default_str();
    renderCmd
        ->add_option("--splash-radius", renderOpts.splash.spriteRadius,
                     "splash sprite radius, metres")
        ->capture_default_str();
    renderCmd
        ->add_option("--splash-spread", renderOpts.splash.spawnRadius,
                     "radius of the sphere artificial splashes start in, metres")
        ->capture_default_str();
    renderCmd->add_flag("--no-splashes", renderOpts.noSplashes, "skip the splash pass");
    renderCmd->add_option("--sheet-frames", renderOpts.sheetFrames, "frames on the contact sheet")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    renderCmd
        ->add_option("--png-level", renderOpts.pngCompression,
                     "zlib level of the frame PNGs (0..9)")
        ->capture_default_str()
        ->check(CLI::Range(0, 9));

    Options fidelity;
    FidelityOptions fidelityOpts;
    auto* fidelityCmd = app.add_subcommand(
        "fidelity", "measure the replay against the simulated surface (F = 0 and F > 0) and the "
                    "continuity of a long replay");
    addCommon(fidelityCmd, fidelity);
    addFidelityOptions(fidelityCmd, fidelityOpts);

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
        preferLlvmpipeThreads();
        int rc = 0;
        if (*benchCmd)
            rc = runBench(bench, frames, warmup, errorFrames, cpuFrames, referenceCache);
        else if (*renderCmd)
            rc = runRender(render, renderOpts);
        else if (*fidelityCmd)
            rc = runFidelity(fidelity, fidelityOpts);
        else
            rc = runHeights(heights, outDir, seconds);
        for (const std::string& note : pendingNotes())
            std::cerr << "swell-play: note: " << note << "\n";
        return rc;
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
