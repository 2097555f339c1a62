#pragma once
// A replay of one cache for embedding (the C API swell.h and the Python module wrap it): the
// timeline over the cache (timeline.h), one slice sampler per slice set, every frame the
// timeline can show decoded once, the GPU replay of the mode (mode_replay.h) and its splash
// sprites (Sec. 5). Advance to a simulated time, then read the height field, sample it at
// points, or read the splashes. swell-play's programs set up the same pieces themselves
// (they decode only the frames of the output times they know in advance).

#include "swell/cache/reader.h"
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/modes/mode_params.h"
#include "swell/runtime/modes/mode_replay.h"
#include "swell/runtime/render/splash_system.h"
#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/replay_memory.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/slice_sampler.h"
#include "swell/runtime/replay/timeline.h"

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace swell::runtime {

/// swell-play's defaults for `mode`: the paper's Table 4 (paperDefaults) with the envelope
/// reconstruction and the seamless loop (docs/runtime.md).
ReplayParams playbackDefaults(ReplayMode mode);

/// swell-play's --res auto: one cell per particle spacing over the mesh's x range for
/// `params` (16 .. 4096 cells), or 256 when the cache records no particle spacing.
int autoCells(const cache::Header& header, const ReplayParams& params);

/// The cache frames some entry of `timeline` names (blends included): sorted, unique.
std::vector<std::uint32_t> timelineFrames(const Timeline& timeline);

/// The frames `ids` of `reader`'s cache (ascending), decoded. Throws cache::CacheError.
FrameSet readFrames(const cache::Reader& reader, std::vector<std::uint32_t> ids);

struct PlaybackConfig {
    /// The replay. cellsX or cellsZ <= 0: autoCells for both.
    ReplayParams params = playbackDefaults(ReplayMode::Surging);
    ModeParams mode;     ///< layout (mode.mode must match the defaults chosen for params)
    SplashParams splash; ///< splash sprites (Sec. 5)
    /// GiB the replay may hold (replay_memory.h; JSON key "memory_budget_gib"): a cache whose
    /// timeline needs more is refused at construction, before anything is decoded.
    double memoryBudgetGiB = kDefaultMemoryBudgetGiB;
};

/// A replay chosen by name, as the C API (swell.h) and the Python module take it: the mode's
/// playbackDefaults, then `named` = {"params": {...}, "ripple": {...}, "whirlpool": {...},
/// "splash": {...}} (the keys of replayParamsFromJson, modeParamsFromJson, splashParamsFromJson),
/// then the fields below; "memory_budget_gib" sets PlaybackConfig::memoryBudgetGiB.
struct PlaybackChoice {
    ReplayMode mode = ReplayMode::Surging;
    int cellsX = 0, cellsZ = 0;        ///< the mesh; both 0: autoCells
    std::optional<int> slices;         ///< K; unset: the mode's Table 4 value
    std::optional<double> fluctuation; ///< F; unset: the mode's Table 4 value
    std::uint64_t seed = 1;            ///< noise seed
    nlohmann::json named = nlohmann::json::object();
};

/// The configuration `choice` names. Throws std::invalid_argument naming the key: an unknown or
/// bad key, a mesh with a negative side or only one side 0, or one of the fields above given
/// under "params" too ("set seed in WHERE, not in params": `where` names where the caller sets
/// those fields, e.g. "swell_replay_config").
PlaybackConfig playbackConfig(const PlaybackChoice& choice, std::string_view where);

class Playback {
public:
    /// Plans the timeline, decodes the frames it can show and uploads them. Needs a current GL
    /// 4.5 context (EglContext, or the caller's) on this thread for its whole life. Throws
    /// std::invalid_argument (parameters; a cache too short for them, naming the file),
    /// cache::CacheError (a damaged frame) or RuntimeError (GL).
    Playback(const cache::Reader& reader, PlaybackConfig config);
    Playback(const Playback&) = delete;
    Playback& operator=(const Playback&) = delete;

    /// Computes the surface at `seconds` of simulated time from the timeline's start (tau =
    /// seconds / time unit, eq. (5)); returns without waiting for the GPU. Throws
    /// std::invalid_argument for a non-finite time.
    void advance(double seconds);
    /// The simulated time of the last advance() (0 before the first: advance(0) runs then).
    double seconds() const { return m_seconds; }

    /// The height field at seconds() (read back from the GPU once per advance).
    const HeightField& heights();
    /// Heights at points (height_sampling.h: bilinear, NaN outside the mesh) at seconds().
    void sample(std::span<const double> x, std::span<const double> z, std::span<double> out);
    /// The splash sprites at seconds(): real splash particles of every real slice's frame and
    /// their artificial companions (splash_system.h), placed in the mode's layout.
    std::vector<SplashSprite> splashes() const;

    /// The GPU's height buffer / R32F texture (mode_replay.h), valid until the next advance.
    GlName heightBuffer() const { return m_gpu->heightBuffer(); }
    GlName heightTexture() { return m_gpu->heightTexture(); }
    void finish() const { m_gpu->finish(); }

    const Grid& grid() const { return m_gpu->grid(); }
    const PlaybackConfig& config() const { return m_config; }
    const TimelinePlan& plan() const { return m_plan; }
    const FrameSet& frames() const { return m_frames; }
    /// Bytes uploaded to the GPU (frames, column sums).
    std::size_t uploadedBytes() const { return m_gpu->uploadedBytes(); }

private:
    void ensureAdvanced();

    PlaybackConfig m_config;
    TimelinePlan m_plan;
    std::vector<SliceSampler> m_samplers;
    FrameSet m_frames; // the splash systems keep a reference: never moved after construction
    std::unique_ptr<ModeReplay> m_gpu;
    std::vector<SplashSystem> m_splashes;
    double m_seconds = 0.0;
    bool m_advanced = false;
    bool m_heightsRead = false;
    HeightField m_heights;
};

/// A Playback with the GL context it lives in: a headless one of its own (EglContext), or the
/// caller's current one (requireCurrentContext checks it). playback() makes the own context
/// current first, so several sessions can share a thread, and the session is destroyed in it.
/// The replay of the C API and of the Python module.
class PlaybackSession {
public:
    enum class Context { Own, Current };

    /// Throws as Playback, and RuntimeError when Context::Current finds no usable context.
    PlaybackSession(const cache::Reader& reader, PlaybackConfig config, Context context);
    ~PlaybackSession();
    PlaybackSession(const PlaybackSession&) = delete;
    PlaybackSession& operator=(const PlaybackSession&) = delete;

    Playback& playback();
    const Playback& playback() const;
    /// The own context, or null with the caller's.
    const EglContext* context() const { return m_context ? &*m_context : nullptr; }

private:
    std::optional<EglContext> m_context;
    std::unique_ptr<Playback> m_playback;
};

} // namespace swell::runtime
