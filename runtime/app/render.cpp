// swell-play render (Sec. 5): shaded frames (reflection, refraction, Fresnel, splash sprites) as
// PNGs, a contact sheet, an optional mp4 and per-frame exports, with render.json recording every
// parameter, the camera and the stage timings (docs/render.md).

#include "command.h"
#include "play_common.h"
#include "process.h"

#include "swell/cache/output_lock.h"
#include "swell/runtime/error.h"
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/io/atomic_write.h"
#include "swell/runtime/io/exporters.h"
#include "swell/runtime/io/height_sequence.h"
#include "swell/runtime/modes/mode_replay.h"
#include "swell/runtime/modes/mode_splashes.h"
#include "swell/runtime/render/splash_system.h"
#include "swell/runtime/render/water_renderer.h"
#include "swell/runtime/replay/fidelity.h"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iostream>

namespace swell::play {
namespace {

using namespace swell::runtime;
namespace fs = std::filesystem;

/// Options of `swell-play render` beyond the shared ones.
struct RenderOptions {
    std::string outDir;            ///< output folder
    std::string size = "1280x720"; ///< image width x height
    double seconds = 3.0;          ///< simulated seconds to render
    std::string video;             ///< mp4 to encode with ffmpeg (empty: none)
    std::string exports;           ///< comma list: heights, normals, blender-disp, mesh, splashes
    std::string skyDir;            ///< folder with px, nx, py, ny, pz, nz .png (empty: procedural)
    std::vector<double> eye;       ///< camera position x y z (empty: default framing)
    std::vector<double> target;    ///< camera target x y z (empty: default framing)
    double fov = 40.0;             ///< vertical field of view, degrees
    int sheetFrames = 6;           ///< frames on the contact sheet
    int pngCompression = 1;        ///< zlib level of the frame PNGs
    bool noSplashes = false;       ///< skip the splash pass
    std::string splashes = "auto"; ///< --splashes: auto (not in the whirlpool), on or off
    ShadingParams shading;         ///< shading (size and samples are set from the options)
    SplashParams splash;           ///< splash particles (Sec. 5)
    SkyParams sky;                 ///< procedural sky and sun
    std::string heightsFormat = "png16"; ///< --heights-format: png16, exr-half, exr-float
    // Resolved by finish():
    bool exportHeights = false, exportMesh = false, exportSplashes = false;
    HeightSequenceParams heights; ///< what heights/ holds (normals, displacement, format)

    /// Checks and resolves the string options; throws std::invalid_argument naming the option.
    void finish(ReplayMode mode, double fps) {
        int width = 0, height = 0;
        char x = 0, extra = 0;
        if (std::sscanf(size.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 ||
            (x != 'x' && x != 'X')) {
            throw std::invalid_argument(
                fmt::format("--size must look like 1280x720, got '{}'", size));
        }
        shading.width = width;
        shading.height = height;
        shading.validate();
        if (splashes != "auto" && splashes != "on" && splashes != "off")
            throw std::invalid_argument(
                fmt::format("--splashes must be auto, on or off, got '{}'", splashes));
        // The whirlpool's spirals carry the bake's spray at one x to one radius: a ring.
        splash.enabled =
            !noSplashes && splashes != "off" && (splashes == "on" || mode != ReplayMode::Whirlpool);
        splash.validate();
        sky.validate();
        checkSeconds(seconds, fps);
        for (std::size_t start = 0; start < exports.size();) {
            const std::size_t end = std::min(exports.find(',', start), exports.size());
            const std::string item = exports.substr(start, end - start);
            bool* flag = item == "heights"        ? &exportHeights
                         : item == "normals"      ? &heights.normals
                         : item == "blender-disp" ? &heights.displacement
                         : item == "mesh"         ? &exportMesh
                         : item == "splashes"     ? &exportSplashes
                                                  : nullptr;
            if (flag == nullptr && !item.empty()) {
                throw std::invalid_argument(fmt::format(
                    "--export takes heights, normals, blender-disp, mesh, splashes; got '{}'",
                    item));
            }
            if (flag != nullptr)
                *flag = true;
            start = end + 1;
        }
        // Normal maps and the displacement go into heights/ with the height maps they belong to.
        exportHeights = exportHeights || heights.normals || heights.displacement;
        heights.format = parseHeightFormat(heightsFormat, "--heights-format");
        if (eye.empty() != target.empty())
            throw std::invalid_argument("--camera and --target go together");
        Camera::checkFov(fov); // "camera fov ...": --fov in the user's words (option_words.h)
        if (!video.empty() && video.find(".mp4") == std::string::npos)
            throw std::invalid_argument(
                fmt::format("--video must name an .mp4 file, got '{}'", video));
    }
};

Vec3 toVec3(const std::vector<double>& v, const char* what) {
    if (v.size() != 3)
        throw std::invalid_argument(fmt::format("{} needs three numbers x y z", what));
    return {v[0], v[1], v[2]};
}

json vec3Json(const Vec3& v) {
    return json::array({v[0], v[1], v[2]});
}

/// Timings summed over the frames (ms).
struct RenderTotals {
    double drawMs = 0.0, drawCpuMs = 0.0, timedDrawMs = 0.0, spriteMs = 0.0, readMs = 0.0,
           writeMs = 0.0, exportMs = 0.0, totalMs = 0.0;
    std::size_t timedFrames = 0, sprites = 0, culled = 0;
    StageTimes stages; ///< replay and render passes of the timed frames
};

/// One render run: the replay, the renderer, the splash systems and what it has written.
class RenderRun {
public:
    RenderRun(const Options& o, const RenderOptions& r, const ReplaySetup& setup,
              const EglContext& context)
        : m_o(o), m_r(r), m_setup(setup), m_context(context), m_out(r.outDir),
          m_faces(r.skyDir.empty() ? proceduralSky(r.sky) : loadSkyImages(r.skyDir)),
          m_gpu(setup.set, o.params, o.modeParams, setup.samplers), m_camera(makeCamera()),
          m_renderer(m_gpu.grid(), setup.set.header.domain, r.shading, m_faces,
                     sunDirection(r.sky)),
          m_heights(m_out / "heights", r.heights, heightScale(setup.set.header.domain),
                    m_gpu.grid(), displacementReference(setup)),
          // The artificial splashes get their own stream per slice set (the ripple's
          // directions), derived from the run's seed; they follow the mode's layout. A wave
          // maker's own spray is not shown.
          m_splashes(makeSplashSystems(setup.set, m_gpu.grid(),
                                       keepSprayAwayFromTheWaveMaker(r.splash, setup.plan.record),
                                       o.params.seed, setup.samplers.size())) {}

    /// Renders and writes every frame of `taus`, the contact sheet and the video.
    void renderAll(const std::vector<double>& taus, DeferredRenames& staged) {
        const std::size_t count = taus.size();
        const std::size_t sheetCount =
            std::min<std::size_t>(static_cast<std::size_t>(std::max(m_r.sheetFrames, 1)), count);
        Progress progress("swell-play render", count, !m_o.json);
        const auto t0 = Clock::now();
        for (std::size_t i = 0; i < count; ++i) {
            // Stage times (timer queries) on every 8th frame; the frame rate is taken over the
            // others, so the queries do not slow what is measured (not frame 0: set-up).
            const bool timed = i % kTimedEvery == kTimedEvery / 2 || count <= kTimedEvery / 2;
            const std::vector<SplashSprite> sprites = drawFrame(taus[i], secondsOf(m_o, i), timed);
            const bool onSheet =
                m_sheet.size() < sheetCount &&
                i == m_sheet.size() * (count - 1) / std::max<std::size_t>(sheetCount - 1, 1);
            writeFrame(i, taus[i], sprites, onSheet);
            progress.step(i);
        }
        progress.done();
        m_totals.totalMs = msSince(t0);
        writePng(m_out / "contact_sheet.png", contactSheet(m_sheet, 3), 6);
        m_videoStatus = encodeVideo(staged);
    }

    /// Every new file is complete: they replace the old ones now. render.json (and
    /// heights.json) say the folder is whole: the old ones go first, the new ones come last.
    void commit(DeferredRenames& staged) const {
        if (!staged.deferring())
            return;
        fs::remove(m_out / "render.json");
        if (m_r.exportHeights)
            fs::remove(m_out / "heights" / "heights.json");
        staged.commit();
        staged.removeStaleSequenceFiles(); // the folder is this run's set, whole
    }

    /// render.json (and heights/heights.json with --export heights); returns render.json's object.
    json writeRecords() const {
        json meta = paramsJson(m_o, m_setup);
        meta.update(renderRecord());
        meta.update(timingRecord());
        meta["frames"] = m_frames;
        writeTextAtomically(m_out / "render.json",
                            meta.dump(2) + "\n"); // last: the folder is whole
        // The sidecar `swell-play heights` writes, so tools read either folder the same way.
        if (m_r.exportHeights)
            m_heights.writeSidecar(paramsJson(m_o, m_setup), m_context.renderer());
        return meta;
    }

    void printSummary() const {
        const double n = static_cast<double>(m_frames.size());
        const StageTimes st = m_totals.stages.mean(static_cast<int>(m_totals.timedFrames));
        std::cout << fmt::format(
            "swell-play render: {} frames {}x{} ({} samples) in {}, contact sheet {}\n"
            "  {}  ({}, EGL {})\n"
            "  shaded {:.1f} fps (replay + sprites + draw, synced; {:.0f} splash sprites per "
            "frame), {:.1f} frames/s with readback and PNG writing\n"
            "  GPU ms/frame: slice lookup {:.3f}, reconstruct {:.3f}, sky {:.3f}, water {:.3f}, "
            "splashes {:.3f}, resolve {:.3f}; CPU ms/frame: sprites {:.2f}, readback {:.2f}, PNG "
            "{:.2f}\n"
            "  video: {}\n",
            m_frames.size(), m_r.shading.width, m_r.shading.height, m_renderer.samples(),
            m_r.outDir, (m_out / "contact_sheet.png").string(), m_context.renderer(),
            m_context.version(), m_context.platform(), 1000.0 / drawMsPerFrame(),
            static_cast<double>(m_totals.sprites) / n, 1000.0 * n / m_totals.totalMs,
            st.sliceLookupMs, st.reconstructMs, st.skyMs, st.waterMs, st.splashMs, st.resolveMs,
            m_totals.spriteMs / n, m_totals.readMs / n, m_totals.writeMs / n,
            m_r.video.empty() ? m_videoStatus : m_r.video + " (" + m_videoStatus + ")");
    }

private:
    static constexpr std::size_t kTimedEvery = 8;

    Camera makeCamera() const {
        const FrameSet& set = m_setup.set;
        const double waterLevel = set.header.domain.yMin + waterDepth(set);
        // The whirlpool's spirals show best from higher up; the surging and ripple waves from a
        // lower three-quarter view with the horizon behind the block.
        const double elevation =
            m_o.modeParams.mode == ReplayMode::Whirlpool ? 55.0 : kDefaultCameraElevationDegrees;
        Camera camera = defaultCamera(m_gpu.grid(), set.header.domain, waterLevel,
                                      static_cast<double>(m_r.shading.width) / m_r.shading.height,
                                      m_r.fov, elevation);
        if (!m_r.eye.empty()) {
            camera.position = toVec3(m_r.eye, "--camera");
            camera.target = toVec3(m_r.target, "--target");
        }
        camera.validate();
        return camera;
    }

    /// Replays and draws one frame (surface, then the sprites built while it rasterises).
    std::vector<SplashSprite> drawFrame(double tau, double seconds, bool timed) {
        const bool splashes = m_splashes.front().active();
        m_gpu.setTiming(timed);
        m_renderer.setTiming(timed);
        const auto ts = Clock::now();
        const double cpu0 = processCpuMs();
        m_gpu.update(tau);
        m_renderer.drawSurface(m_gpu.heightBuffer(), m_camera, splashes);
        // Each real slice shows its own frame's splashes, the same frame choice as the GPU.
        const auto spritesStart = Clock::now();
        const std::vector<SplashSprite> sprites =
            modeSplashes(m_splashes, m_setup.samplers, m_gpu.grid(), m_o.modeParams, tau, seconds);
        m_totals.spriteMs += msSince(spritesStart);
        m_totals.sprites += sprites.size();
        m_renderer.drawSplashes(sprites, m_r.splash.spriteRadius);
        m_gpu.finish();
        const double frameMs = msSince(ts);
        m_totals.culled += m_renderer.lastCulledSplashCount();
        if (timed) {
            ++m_totals.timedFrames;
            m_totals.timedDrawMs += frameMs;
            m_totals.stages += m_gpu.stageTimes();
            m_totals.stages += m_renderer.stageTimes();
        } else {
            m_totals.drawMs += frameMs;
            m_totals.drawCpuMs += processCpuMs() - cpu0;
        }
        return sprites;
    }

    /// The frame's PNG, its contact-sheet copy, its exports and its render.json entry.
    void writeFrame(std::size_t i, double tau, const std::vector<SplashSprite>& sprites,
                    bool onSheet) {
        auto ts = Clock::now();
        const Image image = m_renderer.readPixels();
        m_totals.readMs += msSince(ts);
        ts = Clock::now();
        const std::string name = fmt::format("frame_{:05d}.png", i);
        writePng(m_out / name, image, m_r.pngCompression);
        if (onSheet) // contact sheet: frames evenly spread, each about 320 px wide
            m_sheet.push_back(downscale(image, std::max(1, m_r.shading.width / 320)));
        m_totals.writeMs += msSince(ts);
        ts = Clock::now();
        const double seconds = secondsOf(m_o, i);
        json entry{{"file", name},
                   {"tau", tau},
                   {"seconds", seconds},
                   {"splash_sprites", sprites.size()},
                   {"splash_sprites_culled", m_renderer.lastCulledSplashCount()}};
        const HeightField field = m_gpu.readHeights();
        // How much wave the frame shows (tools/check_demo holds the demo to it).
        entry["height_spread_m"] = fieldSpread(field);
        entry["flat_rows"] = flatRows(field);
        const std::string what = fmt::format("frame {}, t = {} s", i, seconds);
        if (m_r.exportHeights) {
            const json& written = m_heights.write(i, field, tau, seconds);
            for (const auto& [key, name] :
                 {std::pair{"file", "heights"}, std::pair{"normals", "normals"},
                  std::pair{"disp", "disp"}}) {
                if (written.contains(key))
                    entry[name] = "heights/" + written[key].get<std::string>();
            }
        }
        if (m_r.exportMesh) {
            entry["mesh"] = fmt::format("mesh/surface_{:05d}.ply", i);
            writeSurfacePly(m_out / entry["mesh"].get<std::string>(),
                            makeSurfaceMesh(field, m_gpu.grid()), "swell-play surface, " + what);
        }
        if (m_r.exportSplashes) {
            entry["splashes"] = fmt::format("splashes/splashes_{:05d}.ply", i);
            writeSplashPly(m_out / entry["splashes"].get<std::string>(), sprites,
                           "swell-play splashes, " + what);
        }
        m_totals.exportMs += msSince(ts);
        m_frames.push_back(entry);
    }

    /// Encodes the frames with ffmpeg when asked and installed; the status for render.json.
    /// ffmpeg reads the frames where they are (under their temporary names while `staged`
    /// defers them) and writes the video to a temporary name, which replaces the video path
    /// with the frames: when ffmpeg fails, the render fails and every previous output stays.
    std::string encodeVideo(const DeferredRenames& staged) const {
        if (m_r.video.empty())
            return "not requested";
        const std::string ffmpeg = findOnPath("ffmpeg");
        if (ffmpeg.empty()) {
            std::cerr << "swell-play: ffmpeg not found on PATH: wrote the PNG frames only (install "
                         "ffmpeg for --video)\n";
            return "skipped: ffmpeg not found";
        }
        const fs::path videoPath(m_r.video);
        if (videoPath.has_parent_path())
            fs::create_directories(videoPath.parent_path());
        const fs::path frames = staged.deferring() ? cache::temporaryPath(m_out / "frame_%05d.png")
                                                   : m_out / "frame_%05d.png";
        writeAtomically(videoPath, [&](const fs::path& temporary) {
            const int rc = runProcess({ffmpeg,
                                       "-y",
                                       "-xerror",
                                       "-loglevel",
                                       "error",
                                       "-framerate",
                                       fmt::format("{}", m_o.playbackFps),
                                       "-f",
                                       "image2",
                                       "-c:v",
                                       "png",
                                       "-i",
                                       frames.string(),
                                       "-vf",
                                       "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                       "-c:v",
                                       "libx264",
                                       "-pix_fmt",
                                       "yuv420p",
                                       "-crf",
                                       "20",
                                       "-f",
                                       "mp4",
                                       temporary.string()});
            std::error_code ec;
            if (rc != 0 || fs::file_size(temporary, ec) == 0 || ec) {
                throw RuntimeError(fmt::format("--video {}: ffmpeg failed (exit {}); the previous "
                                               "frames and video are left as they were",
                                               m_r.video, rc));
            }
        });
        return "written";
    }

    /// Frames without timer queries give the frame rate; a render shorter than kTimedEvery + 1
    /// frames has only its first frame apart from them (its first draw includes shader set-up).
    double untimedFrames() const {
        return static_cast<double>(m_frames.size() - m_totals.timedFrames);
    }
    double drawMsPerFrame() const {
        return untimedFrames() > 0
                   ? m_totals.drawMs / untimedFrames()
                   : m_totals.timedDrawMs / static_cast<double>(m_totals.timedFrames);
    }

    json renderRecord() const {
        const RenderOptions& r = m_r;
        const double n = static_cast<double>(m_frames.size());
        return {{"renderer", m_context.renderer()},
                {"llvmpipe_threads", m_context.llvmpipeThreads()},
                {"gl_version", m_context.version()},
                {"egl_platform", m_context.platform()},
                {"size", {r.shading.width, r.shading.height}},
                {"samples", m_renderer.samples()},
                {"seconds", r.seconds},
                {"count", m_frames.size()},
                {"camera",
                 {{"position", vec3Json(m_camera.position)},
                  {"target", vec3Json(m_camera.target)},
                  {"fov_y_degrees", m_camera.fovYDegrees},
                  {"near", m_camera.nearPlane},
                  {"far", m_camera.farPlane}}},
                {"sky",
                 {{"source", r.skyDir.empty() ? std::string("procedural") : r.skyDir},
                  {"sun_azimuth_degrees", r.sky.sunAzimuthDegrees},
                  {"sun_elevation_degrees", r.sky.sunElevationDegrees},
                  {"sun_direction", vec3Json(sunDirection(r.sky))},
                  {"sun_radius_degrees", r.sky.sunRadiusDegrees},
                  {"sun_glow", r.sky.sunGlow},
                  {"cloud_cover", r.sky.cloudCover},
                  {"face_size", m_faces[0].width}}},
                {"shading",
                 {{"refractive_index", r.shading.refractiveIndex},
                  {"absorption_per_m", vec3Json(r.shading.absorption)},
                  {"scatter_colour", vec3Json(r.shading.scatterColour)},
                  {"bed_colour", vec3Json(r.shading.bedColour)},
                  {"sun_shininess", r.shading.sunShininess},
                  {"sun_intensity", r.shading.sunIntensity},
                  {"sides", r.shading.sides}}},
                {"floor",
                 {{"enabled", r.shading.floor.enabled},
                  {"tile_size_m", r.shading.floor.tileSize},
                  {"tile_contrast", r.shading.floor.tileContrast},
                  {"haze_distance_m", r.shading.floor.hazeDistance}}},
                {"splash",
                 {{"active", m_splashes.front().active()},
                  {"artificial_per_real", r.splash.artificialPerReal},
                  {"spawn_radius_m", r.splash.spawnRadius},
                  {"sprite_radius_m", r.splash.spriteRadius},
                  {"velocity_jitter", r.splash.velocityJitter},
                  {"lifetime_s", {r.splash.minLifetime, r.splash.maxLifetime}},
                  {"gravity", r.splash.gravity},
                  {"seed", m_o.params.seed ^ 0x5b1a54e5ULL},
                  {"sprites_mean", static_cast<double>(m_totals.sprites) / n},
                  {"culled_under_water_mean", static_cast<double>(m_totals.culled) / n}}},
                {"exports",
                 {{"heights", r.exportHeights},
                  {"heights_format", heightFormatName(r.heights.format)},
                  {"normals", r.heights.normals},
                  {"blender_disp", r.heights.displacement},
                  {"mesh", r.exportMesh},
                  {"splashes", r.exportSplashes}}},
                {"height_scale",
                 {{"offset", m_heights.scale().offset},
                  {"scale", m_heights.scale().scale},
                  {"units", "m"},
                  {"format", m_heights.formatDescription() +
                                 "; column n = x cell (x = x0 + (n + 0.5) dx), row m = z cell"}}},
                {"x0", m_gpu.grid().x0},
                {"dx", m_gpu.grid().dx},
                {"dz", m_gpu.grid().dz},
                {"video", r.video},
                {"video_status", m_videoStatus},
                {"contact_sheet", "contact_sheet.png"}};
    }

    json timingRecord() const {
        const RenderTotals& t = m_totals;
        const double n = static_cast<double>(m_frames.size());
        const double untimed = untimedFrames();
        const StageTimes st = t.stages.mean(static_cast<int>(t.timedFrames));
        return {{"shaded_fps", 1000.0 / drawMsPerFrame()},
                {"shaded_fps_frames", untimed > 0 ? untimed : static_cast<double>(t.timedFrames)},
                {"timing_ms_per_frame",
                 {{"draw_synced", drawMsPerFrame()},
                  {"draw_cpu", untimed > 0 ? t.drawCpuMs / untimed : 0.0},
                  {"splash_sprites_cpu", t.spriteMs / n},
                  {"readback", t.readMs / n},
                  {"png_write", t.writeMs / n},
                  {"exports", t.exportMs / n},
                  {"total", t.totalMs / n}}},
                {"stage_gpu_ms",
                 {{"slice_lookup", st.sliceLookupMs},
                  {"reconstruct", st.reconstructMs},
                  {"sky", st.skyMs},
                  {"water", st.waterMs},
                  {"splashes", st.splashMs},
                  {"resolve", st.resolveMs},
                  {"timed_frames", t.timedFrames}}}};
    }

    const Options& m_o;
    const RenderOptions& m_r;
    const ReplaySetup& m_setup;
    const EglContext& m_context;
    fs::path m_out;
    CubeFaces m_faces;
    ModeReplay m_gpu;
    Camera m_camera;
    WaterRenderer m_renderer;
    HeightSequence m_heights; ///< heights/ (written with --export heights)
    std::vector<SplashSystem> m_splashes;
    std::vector<Image> m_sheet;
    json m_frames = json::array();
    RenderTotals m_totals;
    std::string m_videoStatus = "not requested";
};

class RenderCommand : public Command {
public:
    CLI::App* add(CLI::App& app) override {
        CLI::App* cmd = addSubcommand(
            app, "render",
            "shaded frames (PNG), contact sheet, optional mp4 and exports (Sec. 5); --res "
            "at most the GL driver's shader-storage block / 4 bytes cells (llvmpipe: "
            "33.5 M, 5792x5792)",
            m_o);
        addRenderOptions(cmd);
        return cmd;
    }

    void check() override {
        finishOptions(m_o);
        m_r.finish(m_o.modeParams.mode, m_o.playbackFps);
    }

    int run() override {
        const cache::Reader reader(m_o.cache);
        resolveFromCache(m_o, reader.header());
        const std::vector<double> taus = outputTaus(m_o, m_r.seconds);
        const double cells = (m_o.params.cellsX + 1.0) * (m_o.params.cellsZ + 1.0);
        const double frameBytes =
            4096.0 + 3.0 * m_r.shading.width * m_r.shading.height +
            (m_r.exportHeights ? heightFrameBytes(m_r.heights, m_o.params.cellsX, m_o.params.cellsZ)
                               : 0.0) +
            (m_r.exportMesh ? 64.0 * cells : 0.0);
        checkDiskSpace(m_r.outDir, static_cast<double>(taus.size()) * frameBytes, taus.size());
        const EglContext context; // first: the driver's limits are checked before any decoding
        WaterRenderer::checkMeshFits(m_o.params.cellsX, m_o.params.cellsZ);
        const ReplaySetup setup = prepareReplay(m_o, reader, taus);
        const fs::path out(m_r.outDir);
        NewFolders folders; // removed again if the render fails
        folders.make(out);
        for (const auto& [on, folder] :
             {std::pair{m_r.exportHeights, "heights"}, std::pair{m_r.exportMesh, "mesh"},
              std::pair{m_r.exportSplashes, "splashes"}}) {
            if (on)
                folders.make(out / folder);
        }
        RenderRun run(m_o, m_r, setup, context);
        // Until every frame, the contact sheet and the exports are complete, they are written
        // under temporary names (atomic_write.h): a failed render leaves the folder as it was.
        DeferredRenames staged;
        run.renderAll(taus, staged);
        json meta = run.writeRecords(); // still staged: replaces the old records with the rest
        run.commit(staged);
        folders.keep();
        if (m_o.json) {
            meta.erase("frames");
            meta["out"] = m_r.outDir;
            std::cout << meta.dump() << "\n";
        } else {
            run.printSummary();
        }
        return 0;
    }

private:
    void addRenderOptions(CLI::App* cmd) {
        RenderOptions& r = m_r;
        cmd->add_option("--out", r.outDir, "output folder")->required();
        cmd->add_option("--size", r.size, "image width x height")->capture_default_str();
        cmd->add_option("--seconds", r.seconds, "simulated seconds to render")
            ->capture_default_str();
        cmd->add_option("--video", r.video, "also encode FILE.mp4 with ffmpeg (when installed)");
        cmd->add_option("--export", r.exports,
                        "per-frame exports, comma list of: heights (heights/: 16-bit PNG or EXR, "
                        "see --heights-format, + JSON), normals (heights/normal_NNNNN.exr), "
                        "blender-disp (heights/disp_NNNN.exr, Blender's Ocean-cache layout), "
                        "mesh (PLY), splashes (PLY)");
        addHeightFormatOption(cmd, r.heightsFormat, "--heights-format");
        cmd->add_option("--samples", r.shading.samples, "multisampling (1: off)")
            ->capture_default_str();
        cmd->add_option("--camera", r.eye,
                        "camera position x y z (metres; default: framing of the domain)")
            ->expected(3);
        cmd->add_option("--target", r.target, "camera target x y z (metres)")->expected(3);
        cmd->add_option("--fov", r.fov, "vertical field of view, degrees")->capture_default_str();
        cmd->add_option(
            "--sky", r.skyDir,
            "folder of six sky images px nx py ny pz nz .png (default: procedural sky)");
        cmd->add_option("--sun-azimuth", r.sky.sunAzimuthDegrees,
                        "sun azimuth, degrees (0 = +x, 90 = +z)")
            ->capture_default_str();
        cmd->add_option("--sun-elevation", r.sky.sunElevationDegrees, "sun elevation, degrees")
            ->capture_default_str();
        cmd->add_option("--splash-count", r.splash.artificialPerReal,
                        "artificial splashes around each real one (Sec. 5)")
            ->capture_default_str();
        cmd->add_option("--splash-radius", r.splash.spriteRadius, "splash sprite radius, metres")
            ->capture_default_str();
        cmd->add_option("--splash-spread", r.splash.spawnRadius,
                        "radius of the sphere artificial splashes start in, metres")
            ->capture_default_str();
        cmd->add_flag("--no-splashes", r.noSplashes, "skip the splash pass (--splashes off)");
        cmd->add_option("--splashes", r.splashes,
                        "splash pass: auto (on, but off in the whirlpool, whose spirals turn the "
                        "bake's spray at one x into a ring), on or off")
            ->capture_default_str();
        cmd->add_option("--sheet-frames", r.sheetFrames, "frames on the contact sheet")
            ->capture_default_str()
            ->check(CLI::Range(1, 64));
        cmd->add_option("--png-level", r.pngCompression, "zlib level of the frame PNGs (0..9)")
            ->capture_default_str()
            ->check(CLI::Range(0, 9));
    }

    Options m_o;
    RenderOptions m_r;
};

} // namespace

std::unique_ptr<Command> makeRenderCommand() {
    return std::make_unique<RenderCommand>();
}

} // namespace swell::play
