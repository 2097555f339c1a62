#pragma once
// What every swell-play subcommand shares: the common options, the replay set-up (timeline,
// samplers, decoded frames) and the parameter record written next to every output.

#include "swell/cache/reader.h"
#include "swell/runtime/io/height_png.h"
#include "swell/runtime/io/height_sequence.h"
#include "swell/runtime/modes/mode_params.h"
#include "swell/runtime/replay/frame_set.h"
#include "swell/runtime/replay/replay_memory.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/slice_sampler.h"
#include "swell/runtime/replay/timeline.h"

#include <CLI/CLI.hpp>

#include "disk_space.h"

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace swell::play {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

/// CPU time of the whole process (every thread, llvmpipe's included), ms.
double processCpuMs();
double msSince(Clock::time_point t0);

/// Options shared by every subcommand.
struct Options {
    std::string cache; ///< input .swell file
    /// N x M base-mesh cells, or "auto": N = M = the water's width over the particle spacing l0
    /// (one cell per particle spacing; 256 when the cache records no l0). docs/runtime.md.
    std::string res = "auto";
    std::string policy = "seamless";         ///< frames outside the window: seamless, loop or clamp
    std::string window = "steady";           ///< frames replayed: steady (the bake's record) or all
    std::string extent = "water";            ///< x range of the grid: water, domain or X0:X1
    std::string reconstruction = "envelope"; ///< column profiles: envelope or paper (eq. 7)
    std::string filter = "low";              ///< noise band: low, high or none
    std::string mode = "surging";            ///< slice layout: surging, ripple or whirlpool
    /// Frames between stored frames: linear or nearest (eq. 5); empty: the mode's default
    /// (linear for surging and ripple, nearest for the whirlpool).
    std::string timeSampling;
    /// Noise defaults of options not given: swell (swellDefaults) or paper (Table 4).
    std::string preset = "swell";
    std::optional<double> eyeDepth; ///< --eye-depth, default by --preset
    double eyeDepthFraction = 0.0;  ///< of the still-water depth (finishOptions)
    double playbackFps = 30.0;      ///< output frames per simulated second
    double start = 0.0;             ///< simulated second of the first frame, from tau = 0
    bool json = false;              ///< one JSON object on stdout
    /// GiB a replay may hold (decoded frames + GPU buffers, replay_memory.h): more fails up
    /// front, or, in heights, is streamed in chunks that fit.
    double memoryBudgetGiB = runtime::kDefaultMemoryBudgetGiB;
    runtime::ReplayParams params;   ///< the replay itself (paper defaults)
    runtime::ModeParams modeParams; ///< ripple directions, whirlpool spirals
    /// Options whose default depends on --mode (Table 4): given explicitly when count() > 0.
    std::vector<
        std::pair<CLI::Option*, void (*)(runtime::ReplayParams&, const runtime::ReplayParams&)>>
        modal;
};

void addCommon(CLI::App* cmd, Options& o);
/// Adds subcommand `name` to `app` with the options every subcommand shares (addCommon).
CLI::App* addSubcommand(CLI::App& app, const std::string& name, const std::string& description,
                        Options& o);
/// The height-map format option `name` (heights --format, render --heights-format): one of
/// runtime::kHeightFormatNames, parsed by runtime::parseHeightFormat when the command runs.
void addHeightFormatOption(CLI::App* cmd, std::string& value, const std::string& name);
/// Resolves the string options into o.params and validates everything.
void finishOptions(Options& o);
/// The options that need the cache: with --res auto the grid (see Options::res), and the
/// whirlpool's eye depth in metres. Errors name the cache file.
void resolveFromCache(Options& o, const cache::Header& header);
/// Animation time of output frame i: (start + i / fps) / time unit (eq. 5's tau); tau = 0 is
/// the timeline's first entry (the steady window's first frame, or the loop's in-frame).
double tauOf(const Options& o, std::size_t i);

/// Simulated second of output frame i: start + i / fps.
double secondsOf(const Options& o, std::size_t i);
/// The animation times of output frames 0 .. count - 1.
std::vector<double> frameTaus(const Options& o, std::size_t count);
/// The animation times of `seconds` of output at o.playbackFps (at least one frame).
std::vector<double> outputTaus(const Options& o, double seconds);
/// The most output frames one run writes or measures (seconds x fps).
inline constexpr double kMaxOutputFrames = 1e6;
/// Throws std::invalid_argument, naming `option` (as typed: "--seconds") and --fps, unless
/// `seconds` is finite and > 0 and `seconds` x `fps` output frames are at most
/// kMaxOutputFrames.
void checkSeconds(double seconds, double fps, const char* option = "--seconds");
/// Throws std::invalid_argument naming --out and what fits when `bytes` (the most `frames`
/// output frames may take, uncompressed) exceed the free space of `out`'s file system.
inline void checkDiskSpace(const std::filesystem::path& out, double bytes, std::size_t frames) {
    cli::checkDiskSpace("--out", out, bytes, frames, "lower --seconds, --fps or the resolution");
}
/// The most bytes one frame of a height sequence (height map, normals, displacement) takes on
/// a mesh of cellsX x cellsZ cells, uncompressed.
double heightFrameBytes(const runtime::HeightSequenceParams& s, int cellsX, int cellsZ);
/// 16-bit PNG scale of a cache's domain: offset yMin, 65535 steps up to yMax.
runtime::HeightScale heightScale(const cache::Domain& domain);

/// "name: i/count frames, ETA s" on stderr while a long command runs (on a terminal only).
class Progress {
public:
    Progress(std::string name, std::size_t count, bool wanted);
    void step(std::size_t i);
    void done();

private:
    std::string m_name;
    std::size_t m_count;
    bool m_on;
    Clock::time_point m_t0;
};

/// A replay ready to run: its timeline, one sampler per slice set and the decoded frames.
struct ReplaySetup {
    runtime::TimelinePlan plan;
    double A = 0.0; ///< cache frames per animation time unit
    std::vector<runtime::SliceSampler> samplers;
    runtime::FrameSet set;
    runtime::ReplayMemory memory; ///< what holding `set` costs, estimated before decoding it
};

/// Plans the timeline over `reader`'s cache (a pending note when the cache records no water
/// extent or steady window), builds the samplers and decodes the frames `taus` select (no
/// other frame is kept). Errors name the cache file.
ReplaySetup prepareReplay(const Options& o, const cache::Reader& reader,
                          const std::vector<double>& taus);
/// Notes for the user collected while setting up (e.g. a cache without the bake's water record),
/// printed on stderr once the command has succeeded (an error stays one line).
std::vector<std::string>& pendingNotes();
/// The timeline over `reader`'s cache for o.params (a pending note when the cache records no
/// water extent or steady window); errors name the cache file.
runtime::TimelinePlan planReplay(const Options& o, const cache::Reader& reader);
/// The slice samplers (one per slice set) of a replay over `plan`.
std::vector<runtime::SliceSampler> samplersOf(const Options& o, const cache::Reader& reader,
                                              const runtime::TimelinePlan& plan);
/// A replay over an already planned timeline (the samplers and the frames `taus` select).
ReplaySetup replayOn(const Options& o, const cache::Reader& reader,
                     const runtime::TimelinePlan& plan, const std::vector<double>& taus);
/// The same with the samplers samplersOf(o, reader, plan) already made (a replay in chunks
/// makes them once).
ReplaySetup replayOn(const Options& o, const cache::Reader& reader,
                     const runtime::TimelinePlan& plan, const std::vector<double>& taus,
                     std::vector<runtime::SliceSampler> samplers);
/// What a replay of frames `ids` over `plan` would hold (replay_memory.h).
runtime::ReplayMemory replayMemory(const Options& o, const cache::Reader& reader,
                                   const runtime::TimelinePlan& plan, std::size_t sliceSets,
                                   std::span<const std::uint32_t> ids);
/// Output frames [first, last) replayed together.
struct Chunk {
    std::size_t first = 0;
    std::size_t last = 0;
};
/// Splits output frames 0 .. taus.size() - 1 into as few consecutive chunks of equal length as
/// keep each chunk's replay within --memory-budget (one chunk when the whole replay fits).
/// Throws the budget error (naming the cache and the budget) when one output frame alone does
/// not fit.
std::vector<Chunk> streamChunks(const Options& o, const cache::Reader& reader,
                                const runtime::TimelinePlan& plan,
                                std::span<const runtime::SliceSampler> samplers,
                                const std::vector<double>& taus);
/// The frames `taus` select from `reader`, for `samplers`.
runtime::FrameSet loadUsed(const cache::Reader& reader,
                           std::span<const runtime::SliceSampler> samplers,
                           const std::vector<double>& taus);

/// Mean water depth of the held frames: mean surface height above the domain's bottom.
double waterDepth(const runtime::FrameSet& set);
/// The level the Blender displacement sequence is measured from: the still-water level the
/// bake recorded (bake_record.h), else y = 0 (the displacement is then the height itself).
runtime::ReferenceLevel displacementReference(const ReplaySetup& setup);
/// Every parameter, the seed, the grid and the timeline (window, loop points) of a replay.
json paramsJson(const Options& o, const ReplaySetup& setup);
double percentile(std::vector<double> v, double q);

} // namespace swell::play
