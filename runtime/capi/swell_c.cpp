// The C API (swell.h) over swell::runtime::Playback: handles own C++ objects, every entry
// point catches everything and turns it into a status and a thread-local message.

#include "swell/swell.h"

#include "swell/cache/error.h"
#include "swell/cache/json_depth.h"
#include "swell/cache/reader.h"
#include "swell/runtime/error.h"
#include "swell/runtime/playback.h"
#include "swell/runtime/replay/bake_record.h"

#include <fmt/format.h>
#include <new>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

struct swell_cache {
    swell::cache::Reader reader;
};

struct swell_replay {
    swell::runtime::PlaybackSession session;
};

namespace {

using swell::runtime::Playback;
using swell::runtime::PlaybackConfig;
using swell::runtime::ReplayMode;

thread_local std::string lastError;

/// The caller's buffer does not fit (SWELL_ERROR_BUFFER_SIZE).
class BufferSizeError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

swell_status fail(swell_status status, std::string message) {
    lastError = std::move(message);
    return status;
}

/// Runs f, mapping every exception to a status (nothing crosses into C).
template <class F> swell_status guarded(const char* function, F&& f) {
    try {
        f();
        lastError.clear();
        return SWELL_OK;
    } catch (const BufferSizeError& e) {
        return fail(SWELL_ERROR_BUFFER_SIZE, e.what());
    } catch (const swell::cache::CacheError& e) {
        return fail(SWELL_ERROR_CACHE, e.what());
    } catch (const swell::runtime::RuntimeError& e) {
        return fail(SWELL_ERROR_GL, e.what());
    } catch (const nlohmann::json::exception& e) {
        return fail(SWELL_ERROR_INVALID_ARGUMENT, fmt::format("params_json: {}", e.what()));
    } catch (const std::invalid_argument& e) {
        return fail(SWELL_ERROR_INVALID_ARGUMENT, e.what());
    } catch (const std::out_of_range& e) {
        return fail(SWELL_ERROR_INVALID_ARGUMENT, e.what());
    } catch (const std::bad_alloc&) {
        return fail(SWELL_ERROR_OUT_OF_MEMORY, fmt::format("{}: out of memory", function));
    } catch (const std::exception& e) {
        return fail(SWELL_ERROR_INTERNAL, fmt::format("{}: {}", function, e.what()));
    } catch (...) {
        return fail(SWELL_ERROR_INTERNAL, fmt::format("{}: unknown exception", function));
    }
}

/// Throws std::invalid_argument naming the argument when p is null.
void need(const void* p, const char* function, const char* argument) {
    if (p == nullptr)
        throw std::invalid_argument(fmt::format("{}: {} is NULL", function, argument));
}

ReplayMode modeOf(swell_mode mode) {
    switch (mode) {
    case SWELL_MODE_SURGING:
        return ReplayMode::Surging;
    case SWELL_MODE_RIPPLE:
        return ReplayMode::Ripple;
    case SWELL_MODE_WHIRLPOOL:
        return ReplayMode::Whirlpool;
    }
    throw std::invalid_argument(
        fmt::format("config.mode: {} is not a swell_mode (0 surging, 1 ripple, 2 whirlpool)",
                    static_cast<int>(mode)));
}

/// The playback configuration of a C config (playbackConfig: the mode's defaults, params_json
/// over them, then the struct's fields).
PlaybackConfig configOf(const swell_replay_config& c) {
    swell::runtime::PlaybackChoice choice;
    choice.mode = modeOf(c.mode);
    if (c.params_json != nullptr) {
        if (const std::string deep = swell::cache::jsonDepthProblem(c.params_json); !deep.empty())
            throw std::invalid_argument("params_json: " + deep);
        choice.named = nlohmann::json::parse(c.params_json);
    }
    if (!choice.named.is_object())
        throw std::invalid_argument("params_json: expected a JSON object");
    choice.cellsX = c.cells_x;
    choice.cellsZ = c.cells_z;
    if (c.slices < 0)
        throw std::invalid_argument(
            fmt::format("config.slices: > 0, or 0 for the mode's default; got {}", c.slices));
    if (c.slices > 0)
        choice.slices = c.slices;
    if (c.fluctuation != c.fluctuation)
        throw std::invalid_argument("config.fluctuation is NaN");
    if (c.fluctuation >= 0.0)
        choice.fluctuation = c.fluctuation;
    choice.seed = c.seed;
    return swell::runtime::playbackConfig(choice, "swell_replay_config");
}

Playback& playbackOf(swell_replay* replay, const char* function) {
    need(replay, function, "replay");
    return replay->session.playback();
}

} // namespace

extern "C" {

const char* swell_version(void) {
    return SWELL_VERSION;
}

const char* swell_last_error(void) {
    return lastError.c_str();
}

const char* swell_status_name(swell_status status) {
    switch (status) {
    case SWELL_OK:
        return "ok";
    case SWELL_ERROR_INVALID_ARGUMENT:
        return "invalid argument";
    case SWELL_ERROR_CACHE:
        return "cache error";
    case SWELL_ERROR_BUFFER_SIZE:
        return "wrong buffer size";
    case SWELL_ERROR_GL:
        return "GL error";
    case SWELL_ERROR_OUT_OF_MEMORY:
        return "out of memory";
    case SWELL_ERROR_INTERNAL:
        return "internal error";
    }
    return "unknown status";
}

swell_status swell_cache_open(const char* path, swell_cache** out) {
    return guarded("swell_cache_open", [&] {
        need(out, "swell_cache_open", "out");
        *out = nullptr;
        need(path, "swell_cache_open", "path");
        *out = new swell_cache{swell::cache::Reader(path)};
    });
}

swell_status swell_cache_info_get(const swell_cache* cache, swell_cache_info* out) {
    return guarded("swell_cache_info_get", [&] {
        need(cache, "swell_cache_info_get", "cache");
        need(out, "swell_cache_info_get", "out");
        const swell::cache::Header& h = cache->reader.header();
        const swell::runtime::BakeRecord record = swell::runtime::bakeRecord(h);
        *out = swell_cache_info{};
        out->frame_count = cache->reader.frameCount();
        out->frame_seconds = h.dt * h.frameInterval;
        out->x_min = h.domain.xMin;
        out->x_max = h.domain.xMax;
        out->y_min = h.domain.yMin;
        out->y_max = h.domain.yMax;
        out->particle_spacing = record.particleSpacing;
        out->steady_start_seconds = record.steadyStartSeconds;
    });
}

void swell_cache_close(swell_cache* cache) {
    delete cache;
}

void swell_replay_config_default(swell_replay_config* config) {
    if (config == nullptr)
        return;
    *config = swell_replay_config{};
    config->mode = SWELL_MODE_SURGING;
    config->fluctuation = -1.0;
    config->seed = 1;
    config->context = SWELL_CONTEXT_HEADLESS;
}

swell_status swell_replay_create(const swell_cache* cache, const swell_replay_config* config,
                                 swell_replay** out) {
    return guarded("swell_replay_create", [&] {
        need(out, "swell_replay_create", "out");
        *out = nullptr;
        need(cache, "swell_replay_create", "cache");
        need(config, "swell_replay_create", "config");
        if (config->context != SWELL_CONTEXT_HEADLESS && config->context != SWELL_CONTEXT_CURRENT)
            throw std::invalid_argument(fmt::format("config.context: {} is not a swell_context",
                                                    static_cast<int>(config->context)));
        const auto context = config->context == SWELL_CONTEXT_HEADLESS
                                 ? swell::runtime::PlaybackSession::Context::Own
                                 : swell::runtime::PlaybackSession::Context::Current;
        *out = new swell_replay{
            swell::runtime::PlaybackSession(cache->reader, configOf(*config), context)};
    });
}

void swell_replay_destroy(swell_replay* replay) {
    delete replay; // the session deletes its GL objects in their own context
}

swell_status swell_replay_grid(const swell_replay* replay, swell_grid* out) {
    return guarded("swell_replay_grid", [&] {
        need(replay, "swell_replay_grid", "replay");
        need(out, "swell_replay_grid", "out");
        const swell::runtime::Grid& g = replay->session.playback().grid();
        *out = swell_grid{g.cellsX, g.cellsZ, g.x0, g.dx, g.dz, g.extentZ};
    });
}

swell_status swell_replay_advance(swell_replay* replay, double seconds) {
    return guarded("swell_replay_advance",
                   [&] { playbackOf(replay, "swell_replay_advance").advance(seconds); });
}

swell_status swell_replay_finish(swell_replay* replay) {
    return guarded("swell_replay_finish",
                   [&] { playbackOf(replay, "swell_replay_finish").finish(); });
}

swell_status swell_replay_heights(swell_replay* replay, float* heights, size_t count) {
    return guarded("swell_replay_heights", [&] {
        Playback& p = playbackOf(replay, "swell_replay_heights");
        need(heights, "swell_replay_heights", "heights");
        const swell::runtime::HeightField& field = p.heights();
        if (count != field.heights.size())
            throw BufferSizeError(fmt::format(
                "swell_replay_heights: the buffer holds {} floats, the grid has {} x {} = {} cells",
                count, field.cellsX, field.cellsZ, field.heights.size()));
        for (std::size_t i = 0; i < count; ++i)
            heights[i] = static_cast<float>(field.heights[i]);
    });
}

swell_status swell_replay_sample(swell_replay* replay, const double* x, const double* z,
                                 size_t count, double* heights) {
    return guarded("swell_replay_sample", [&] {
        Playback& p = playbackOf(replay, "swell_replay_sample");
        if (count == 0)
            return;
        need(x, "swell_replay_sample", "x");
        need(z, "swell_replay_sample", "z");
        need(heights, "swell_replay_sample", "heights");
        p.sample({x, count}, {z, count}, {heights, count});
    });
}

swell_status swell_replay_splashes(swell_replay* replay, swell_splash* out, size_t capacity,
                                   size_t* count) {
    return guarded("swell_replay_splashes", [&] {
        Playback& p = playbackOf(replay, "swell_replay_splashes");
        need(count, "swell_replay_splashes", "count");
        if (capacity > 0)
            need(out, "swell_replay_splashes", "out");
        const std::vector<swell::runtime::SplashSprite> sprites = p.splashes();
        *count = sprites.size();
        if (out == nullptr)
            return; // only the count was asked for
        const std::size_t n = std::min(capacity, sprites.size());
        for (std::size_t i = 0; i < n; ++i)
            out[i] = swell_splash{sprites[i].x, sprites[i].y, sprites[i].z, sprites[i].alpha};
        if (capacity < sprites.size())
            throw BufferSizeError(
                fmt::format("swell_replay_splashes: {} sprites, the buffer holds {}",
                            sprites.size(), capacity));
    });
}

swell_status swell_replay_height_texture(swell_replay* replay, unsigned* texture) {
    return guarded("swell_replay_height_texture", [&] {
        Playback& p = playbackOf(replay, "swell_replay_height_texture");
        need(texture, "swell_replay_height_texture", "texture");
        *texture = p.heightTexture();
    });
}

} // extern "C"
