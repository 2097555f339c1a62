#include "play_common.h"

#include "swell/runtime/playback.h"
#include "swell/runtime/replay/bake_record.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <iostream>
#include <sys/resource.h>
#include <unistd.h>

namespace swell::play {

using namespace swell::runtime;

double processCpuMs() {
    rusage u{};
    ::getrusage(RUSAGE_SELF, &u);
    return 1e3 * (static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec)) +
           1e-3 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

void addHeightFormatOption(CLI::App* cmd, std::string& value, const std::string& name) {
    cmd->add_option(name, value,
                    "height maps: png16 (16-bit greyscale height_NNNNN.png, scaled to the "
                    "domain), exr-half or exr-float (height_NNNNN.exr: one channel Y, metres, "
                    "ZIP)")
        ->capture_default_str();
}

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
    cmd->add_option("--eye-depth", o.eyeDepth,
                    "whirlpool: depth of the funnel at the eye, a fraction of the still-water "
                    "depth, 0 .. 1 (0: the paper's flat eye; default 0.5, 0 with --preset "
                    "paper)");
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
    cmd->add_option("--policy", o.policy,
                    "frames past the window's ends: seamless (loop between the two most alike "
                    "frames with a cross-fade), loop (jump back) or clamp")
        ->capture_default_str();
    cmd->add_option("--window", o.window,
                    "frames replayed: steady (from the bake's recorded steady start) or all")
        ->capture_default_str();
    cmd->add_option("--crossfade", o.params.crossfadeSeconds,
                    "seamless loop: cross-fade length, simulated seconds")
        ->capture_default_str();
    cmd->add_option("--extent", o.extent,
                    "x range of the grid: water (the bake's recorded water extent), domain (the "
                    "whole cache domain) or X0:X1 in metres")
        ->capture_default_str();
    cmd->add_option("--reconstruction", o.reconstruction,
                    "column profiles: envelope (the frame's free surface) or paper (eq. 7's "
                    "Gaussian mean of the surface particles in [3 dx))")
        ->capture_default_str();
    cmd->add_option("--preset", o.preset,
                    "defaults of -F, --beta, --cutoff, --slices and --time-sampling not given: "
                    "swell (surging: F 0.07, beta 4, cut-off 4, linear time; long crests) or "
                    "paper (Table 4, eq. 5's nearest frame)")
        ->capture_default_str();
    cmd->add_option("--time-sampling", o.timeSampling,
                    "what a slice shows between two stored frames: linear (the two frames' "
                    "profiles blended by the fraction of eq. (5)'s frame number) or nearest "
                    "(eq. 5's nearest frame, the paper); default linear, nearest with "
                    "--preset paper");
    cmd->add_option("--sigma", o.params.sigma, "Gaussian sigma of eq. (7), cells")
        ->capture_default_str();
    cmd->add_option("--fps", o.playbackFps, "output frames per simulated second")
        ->capture_default_str();
    cmd->add_option("--start", o.start,
                    "simulated second of the first frame, counted from the steady start (the "
                    "loop's in-frame with --policy seamless)")
        ->capture_default_str();
    cmd->add_option("--memory-budget", o.memoryBudgetGiB,
                    "GiB the replay may hold (decoded frames + GPU buffers, estimated before "
                    "anything is decoded): more is an error up front; heights streams its "
                    "frames in chunks that fit instead")
        ->capture_default_str();
    cmd->add_flag("--json", o.json, "print one JSON object on stdout");
}

CLI::App* addSubcommand(CLI::App& app, const std::string& name, const std::string& description,
                        Options& o) {
    CLI::App* cmd = app.add_subcommand(name, description);
    addCommon(cmd, o);
    return cmd;
}

/// Resolves the string options into o.params and validates everything.
void finishOptions(Options& o) {
    int n = 0, m = 0;
    char x = 0, extra = 0;
    if (o.res == "auto") {
        n = m = 256; // resolveFromCache sets it from the cache
    } else if (std::sscanf(o.res.c_str(), "%d%c%d%c", &n, &x, &m, &extra) != 3 ||
               (x != 'x' && x != 'X')) {
        throw std::invalid_argument(
            fmt::format("--res must be auto or look like 128x128, got '{}'", o.res));
    }
    o.params.cellsX = n;
    o.params.cellsZ = m;
    o.modeParams.mode = replayModeFromString(o.mode);
    if (o.preset != "swell" && o.preset != "paper")
        throw std::invalid_argument(
            fmt::format("--preset must be swell or paper, got '{}'", o.preset));
    const ReplayParams table4 =
        o.preset == "paper" ? paperDefaults(o.modeParams.mode) : swellDefaults(o.modeParams.mode);
    for (const auto& [option, copy] : o.modal) {
        if (option->count() == 0)
            copy(o.params, table4); // not given: the mode's Table 4 value
    }
    o.params.policy = framePolicyFromString(o.policy);
    if (o.window != "steady" && o.window != "all")
        throw std::invalid_argument(
            fmt::format("--window must be steady or all, got '{}'", o.window));
    o.params.steadyWindow = o.window == "steady";
    o.params.reconstruction = reconstructionFromString(o.reconstruction);
    // The paper's whirlpool has a flat eye; metres once the cache is open (resolveFromCache).
    o.eyeDepthFraction = o.eyeDepth.value_or(o.preset == "paper" ? 0.0 : 0.5);
    if (!(o.eyeDepthFraction >= 0.0 && o.eyeDepthFraction <= 1.0))
        throw std::invalid_argument(
            fmt::format("--eye-depth must be a fraction 0 .. 1 of the still-water depth, got {}",
                        o.eyeDepthFraction));
    if (o.timeSampling.empty()) {
        o.params.timeSampling = o.preset == "paper" ? TimeSampling::Nearest : TimeSampling::Linear;
    } else if (o.timeSampling == "linear" || o.timeSampling == "nearest") {
        o.params.timeSampling = timeSamplingFromString(o.timeSampling);
    } else {
        throw std::invalid_argument(
            fmt::format("--time-sampling must be linear or nearest, got '{}'", o.timeSampling));
    }
    if (o.extent == "water") {
        o.params.extentX = ExtentX::Water;
    } else if (o.extent == "domain") {
        o.params.extentX = ExtentX::Domain;
    } else {
        double x0 = 0.0, x1 = 0.0;
        char colon = 0, extra2 = 0;
        if (std::sscanf(o.extent.c_str(), "%lf%c%lf%c", &x0, &colon, &x1, &extra2) != 3 ||
            colon != ':') {
            throw std::invalid_argument(fmt::format(
                "--extent must be water, domain or X0:X1 (metres), got '{}'", o.extent));
        }
        o.params.extentX = ExtentX::Explicit;
        o.params.extentX0 = x0;
        o.params.extentX1 = x1;
    }
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
    (void)budgetBytes(o.memoryBudgetGiB, "--memory-budget");
    o.params.validate();
    o.modeParams.validate();
}

/// Animation time of output frame i: simulated time / time unit (eq. 5's tau).
double tauOf(const Options& o, std::size_t i) {
    return (o.start + static_cast<double>(i) / o.playbackFps) / o.params.timeUnitSeconds;
}

FrameSet loadUsed(const cache::Reader& reader, std::span<const SliceSampler> samplers,
                  const std::vector<double>& taus) {
    return readFrames(reader, framesUsed(samplers, taus));
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

ReferenceLevel displacementReference(const ReplaySetup& setup) {
    const double still = setup.plan.record.stillWaterLevel;
    if (std::isfinite(still))
        return {still, "still_water_level: the still-water surface the bake recorded"};
    return {0.0, "y = 0: the cache records no still-water level (G is the height itself)"};
}

void resolveFromCache(Options& o, const cache::Header& header) {
    // The eye's depth: a fraction of the still water's depth above the tank floor (half the
    // domain's height when the cache records no still-water level).
    BakeRecord record;
    try {
        record = bakeRecord(header);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(fmt::format("{}: {}", o.cache, e.what()));
    }
    const double still = record.stillWaterLevel;
    const double depth = std::isfinite(still) && still > record.floorLevel
                             ? still - record.floorLevel
                             : 0.5 * (static_cast<double>(header.domain.yMax) - header.domain.yMin);
    o.modeParams.whirlpool.eyeDepth = o.eyeDepthFraction * depth;
    if (o.res != "auto")
        return;
    const int n = autoCells(header, o.params);
    o.params.cellsX = o.params.cellsZ = n;
    o.res = fmt::format("{}x{}", n, n);
}

std::vector<std::string>& pendingNotes() {
    static std::vector<std::string> notes;
    return notes;
}

double secondsOf(const Options& o, std::size_t i) {
    return o.start + static_cast<double>(i) / o.playbackFps;
}

std::vector<double> frameTaus(const Options& o, std::size_t count) {
    std::vector<double> taus(count);
    for (std::size_t i = 0; i < count; ++i)
        taus[i] = tauOf(o, i);
    return taus;
}

std::vector<double> outputTaus(const Options& o, double seconds) {
    return frameTaus(o,
                     static_cast<std::size_t>(std::max(1.0, std::round(seconds * o.playbackFps))));
}

void checkSeconds(double seconds, double fps, const char* option) {
    if (!(seconds > 0.0) || !std::isfinite(seconds))
        throw std::invalid_argument(fmt::format("{} must be > 0, got {}", option, seconds));
    if (std::round(seconds * fps) > kMaxOutputFrames) {
        throw std::invalid_argument(fmt::format(
            "{} {} x --fps {} asks for {:.0f} output frames; at most {:.0f} fit in one run "
            "({} up to {:g} at --fps {})",
            option, seconds, fps, std::round(seconds * fps), kMaxOutputFrames, option,
            kMaxOutputFrames / fps, fps));
    }
}

double heightFrameBytes(const HeightSequenceParams& s, int cellsX, int cellsZ) {
    const double samples = (cellsX + 1.0) * (cellsZ + 1.0);
    const double sample = s.format == HeightFormat::ExrFloat ? 4.0 : 2.0;
    const double exr = s.exrPixelType() == ExrPixelType::Half ? 2.0 : 4.0;
    return 4096.0 +
           samples * (sample + (s.normals ? 3.0 * exr : 0.0) + (s.displacement ? 3.0 * exr : 0.0));
}

HeightScale heightScale(const cache::Domain& d) {
    return {d.yMin, (static_cast<double>(d.yMax) - d.yMin) / 65535.0};
}

Progress::Progress(std::string name, std::size_t count, bool wanted)
    : m_name(std::move(name)), m_count(count), m_on(wanted && ::isatty(2) != 0),
      m_t0(Clock::now()) {}

void Progress::step(std::size_t i) {
    if (!m_on)
        return;
    const double eta =
        msSince(m_t0) / 1000.0 * static_cast<double>(m_count - i - 1) / static_cast<double>(i + 1);
    std::cerr << fmt::format("\r{}: {}/{} frames, ETA {:.0f} s ", m_name, i + 1, m_count, eta);
}

void Progress::done() {
    if (m_on)
        std::cerr << "\n";
}

ReplayMemory replayMemory(const Options& o, const cache::Reader& reader, const TimelinePlan& plan,
                          std::size_t sliceSets, std::span<const std::uint32_t> ids) {
    return estimateReplayMemory(reader, ids, o.params, sliceSets, plan.timeline);
}

namespace {

void checkBudget(const Options& o, const ReplayMemory& m, const std::string& what) {
    checkMemoryBudget(m, budgetBytes(o.memoryBudgetGiB, "--memory-budget"),
                      fmt::format("{}: {}", o.cache, what), "--memory-budget",
                      "raise it, lower --res, or replay fewer --seconds / --frames");
}

} // namespace

std::vector<SliceSampler> samplersOf(const Options& o, const cache::Reader& reader,
                                     const TimelinePlan& plan) {
    return makeSamplers(o.params, o.modeParams, plan.timeline,
                        framesPerTimeUnit(reader.header(), o.params));
}

ReplaySetup replayOn(const Options& o, const cache::Reader& reader, const TimelinePlan& plan,
                     const std::vector<double>& taus) {
    return replayOn(o, reader, plan, taus, samplersOf(o, reader, plan));
}

ReplaySetup replayOn(const Options& o, const cache::Reader& reader, const TimelinePlan& plan,
                     const std::vector<double>& taus, std::vector<SliceSampler> samplers) {
    ReplaySetup s;
    s.plan = plan;
    s.A = framesPerTimeUnit(reader.header(), o.params);
    s.samplers = std::move(samplers);
    const std::vector<std::uint32_t> ids = framesUsed(s.samplers, taus);
    s.memory = replayMemory(o, reader, plan, s.samplers.size(), ids);
    checkBudget(o, s.memory, "this replay");
    s.set = readFrames(reader, ids);
    return s;
}

std::vector<Chunk> streamChunks(const Options& o, const cache::Reader& reader,
                                const TimelinePlan& plan, std::span<const SliceSampler> samplers,
                                const std::vector<double>& taus) {
    const std::size_t budget = budgetBytes(o.memoryBudgetGiB, "--memory-budget");
    auto fits = [&](std::size_t first, std::size_t last) {
        const std::vector<std::uint32_t> ids =
            framesUsed(samplers, std::span(taus).subspan(first, last - first));
        return replayMemory(o, reader, plan, samplers.size(), ids).total() <= budget;
    };
    for (std::size_t count = 1;; count *= 2) {
        const std::size_t length = (taus.size() + count - 1) / count;
        std::vector<Chunk> chunks;
        bool ok = true;
        for (std::size_t first = 0; first < taus.size() && ok; first += length) {
            chunks.push_back({first, std::min(first + length, taus.size())});
            ok = fits(chunks.back().first, chunks.back().last);
        }
        if (ok)
            return chunks;
        if (length == 1)
            break;
    }
    // Not even one output frame fits: the error names what the worst one needs.
    ReplayMemory worst;
    for (std::size_t i = 0; i < taus.size(); ++i) {
        const ReplayMemory m = replayMemory(o, reader, plan, samplers.size(),
                                            framesUsed(samplers, std::span(taus).subspan(i, 1)));
        if (m.total() > worst.total())
            worst = m;
    }
    checkBudget(o, worst, "one output frame alone");
    return {{0, taus.size()}}; // unreachable: the check above throws
}

TimelinePlan planReplay(const Options& o, const cache::Reader& reader) {
    TimelinePlan plan;
    try {
        plan = planTimeline(reader.header(), reader.frameCount(), o.params,
                            [&](std::uint32_t id) { return reader.readFrame(id); });
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(fmt::format("{}: {}", o.cache, e.what()));
    }
    if (!plan.record.note.empty()) {
        const std::string note = fmt::format("{}: {}", o.cache, plan.record.note);
        if (std::find(pendingNotes().begin(), pendingNotes().end(), note) == pendingNotes().end())
            pendingNotes().push_back(note);
    }
    return plan;
}

ReplaySetup prepareReplay(const Options& o, const cache::Reader& reader,
                          const std::vector<double>& taus) {
    return replayOn(o, reader, planReplay(o, reader), taus);
}

json paramsJson(const Options& o, const ReplaySetup& setup) {
    const FrameSet& set = setup.set;
    const double A = setup.A;
    const ReplayParams& p = o.params;
    const Grid grid = makeGrid(set.header, p);
    const BakeRecord& rec = setup.plan.record;
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
            {"frames_decoded", set.ids.size()},
            {"reconstruction", o.reconstruction},
            {"time_sampling", toString(p.timeSampling)},
            {"preset", o.preset},
            {"grid_x",
             {{"x0", grid.x0},
              {"x1", grid.x0 + grid.cellsX * grid.dx},
              {"dx", grid.dx},
              {"extent", o.extent}}},
            {"bake_record",
             {{"recorded", rec.recorded},
              {"water_x", {rec.waterXMin, rec.waterXMax}},
              {"still_water_level",
               std::isfinite(rec.stillWaterLevel) ? json(rec.stillWaterLevel) : json(nullptr)},
              {"particle_spacing", rec.particleSpacing},
              {"steady_start_s", rec.steadyStartSeconds},
              {"note", rec.note}}},
            {"timeline", toJson(setup.plan)},
            {"memory",
             {{"budget_gib", o.memoryBudgetGiB},
              {"estimate_bytes", setup.memory.total()},
              {"decoded_bytes", setup.memory.decodedBytes},
              {"gpu_bytes", setup.memory.gpuBytes},
              {"upload_copy_bytes", setup.memory.stagingBytes}}}};
}

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const auto hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

} // namespace swell::play
