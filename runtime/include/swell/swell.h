/* swell.h: the C API for embedding swell's replay (docs/embedding.md).
 *
 * Plain C99, opaque handles, no exceptions across the boundary: every function that can fail
 * returns a swell_status, and swell_last_error() gives the message of the last failure on the
 * calling thread (it names the file, parameter or buffer at fault). Link libswell
 * (CMake: swell::swell; pkg-config: swell).
 *
 *   swell_cache* cache;
 *   if (swell_cache_open("surging.swell", &cache) != SWELL_OK) fail(swell_last_error());
 *   swell_replay_config config;
 *   swell_replay_config_default(&config);      // surging, auto resolution, seed 1, headless
 *   config.seed = 7;
 *   swell_replay* replay;
 *   if (swell_replay_create(cache, &config, &replay) != SWELL_OK) fail(swell_last_error());
 *   swell_grid grid;
 *   swell_replay_grid(replay, &grid);
 *   float* heights = malloc(sizeof(float) * grid.cells_x * grid.cells_z);
 *   for (int frame = 0; frame < 100; ++frame) {
 *       swell_replay_advance(replay, frame / 30.0);  // simulated seconds
 *       swell_replay_heights(replay, heights, (size_t)grid.cells_x * grid.cells_z);
 *   }
 *   swell_replay_destroy(replay);
 *   swell_cache_close(cache);
 *
 * Threads: a replay uses the GL context it was created with (its own headless one, or the
 * caller's current one) and must be used on the thread where that context is current. Caches
 * may be shared by replays on one thread. */
#ifndef SWELL_SWELL_H
#define SWELL_SWELL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define SWELL_API __attribute__((visibility("default")))
#else
#define SWELL_API
#endif

typedef enum swell_status {
    SWELL_OK = 0,
    SWELL_ERROR_INVALID_ARGUMENT = 1, /* a null handle or pointer, a parameter out of range */
    SWELL_ERROR_CACHE = 2,            /* a missing, unreadable, damaged or unsupported cache */
    SWELL_ERROR_BUFFER_SIZE = 3,      /* the caller's buffer has the wrong size */
    SWELL_ERROR_GL = 4,               /* no usable GL 4.5 context, or the driver refused */
    SWELL_ERROR_OUT_OF_MEMORY = 5,
    SWELL_ERROR_INTERNAL = 6 /* a bug in swell: please report the message */
} swell_status;

typedef enum swell_mode {
    SWELL_MODE_SURGING = 0,  /* Sec. 4.2: slices across the propagation direction */
    SWELL_MODE_RIPPLE = 1,   /* Sec. 4.4: several directions (params_json "ripple") */
    SWELL_MODE_WHIRLPOOL = 2 /* Sec. 4.5: spiral slices (params_json "whirlpool") */
} swell_mode;

typedef enum swell_context {
    SWELL_CONTEXT_HEADLESS = 0, /* the replay makes its own headless EGL context */
    SWELL_CONTEXT_CURRENT = 1   /* use the caller's current GL 4.5 core context */
} swell_context;

typedef struct swell_cache swell_cache;
typedef struct swell_replay swell_replay;

/* What a cache holds. */
typedef struct swell_cache_info {
    size_t frame_count;
    double frame_seconds; /* simulated seconds between frames */
    double x_min, x_max;  /* domain, metres (x: propagation, y: up) */
    double y_min, y_max;
    double particle_spacing;     /* l0 of the bake, metres (0: not recorded) */
    double steady_start_seconds; /* first steady frame's time (0: not recorded) */
} swell_cache_info;

/* A replay's settings. Start from swell_replay_config_default(), then change fields. */
typedef struct swell_replay_config {
    swell_mode mode;       /* layout; slices 0 and fluctuation < 0 take its Table 4 values */
    int cells_x, cells_z;  /* base mesh N x M; 0: one cell per particle spacing (auto) */
    int slices;            /* K real slices; 0: the mode's default (256, 256, 128) */
    double fluctuation;    /* F of eq. (5); < 0: the mode's default (0.3, 0.4, 0.4) */
    uint64_t seed;         /* noise seed */
    swell_context context; /* whose GL context the replay uses */
    /* Anything else, as JSON (NULL: none), keys as in swell-play's parameter record:
     * {"params": {"sigma": 2, "policy": "loop", "noise": {"beta": 2.5}, ...},
     *  "ripple": {"angles_degrees": [0, 30]}, "whirlpool": {...},
     *  "splash": {"enabled": true, "artificial_per_real": 6},
     *  "memory_budget_gib": 2}  (a replay whose frames need more is refused up front).
     * Unknown keys are errors. */
    const char* params_json;
} swell_replay_config;

/* The base mesh: cell (n, m) is centred at x = x0 + (n + 1/2) dx, z = (m + 1/2) dz; height
 * buffers hold [m * cells_x + n]. */
typedef struct swell_grid {
    int cells_x, cells_z;
    double x0, dx, dz;
    double extent_z; /* cells_z * dz */
} swell_grid;

/* One splash sprite: position in metres (y up) and opacity 0..1. */
typedef struct swell_splash {
    float x, y, z, alpha;
} swell_splash;

/* ------------------------------------------------------------------ errors and version */
SWELL_API const char* swell_version(void);
/* The message of the last failed call on this thread ("" if none). Valid until the next
 * call on this thread. */
SWELL_API const char* swell_last_error(void);
/* "ok", "invalid argument", ... */
SWELL_API const char* swell_status_name(swell_status status);

/* ------------------------------------------------------------------ caches */
/* Opens and validates a cache (header and frame index; frames are checked when read). */
SWELL_API swell_status swell_cache_open(const char* path, swell_cache** out);
SWELL_API swell_status swell_cache_info_get(const swell_cache* cache, swell_cache_info* out);
/* NULL is allowed. Replays made from the cache keep what they need and stay valid. */
SWELL_API void swell_cache_close(swell_cache* cache);

/* ------------------------------------------------------------------ replays */
/* Surging, auto resolution, mode defaults, seed 1, headless context, no JSON. */
SWELL_API void swell_replay_config_default(swell_replay_config* config);
/* Plans the timeline, decodes the frames it can show and uploads them (takes a while on
 * long caches). */
SWELL_API swell_status swell_replay_create(const swell_cache* cache,
                                           const swell_replay_config* config, swell_replay** out);
/* NULL is allowed. With SWELL_CONTEXT_CURRENT the caller's context must still be current. */
SWELL_API void swell_replay_destroy(swell_replay* replay);
SWELL_API swell_status swell_replay_grid(const swell_replay* replay, swell_grid* out);
/* Computes the surface at `seconds` of simulated time from the replay's start (any finite
 * time: the replay loops seamlessly by default). */
SWELL_API swell_status swell_replay_advance(swell_replay* replay, double seconds);
/* Waits until the GPU has finished the last advance (for timing; reading heights waits
 * anyway). */
SWELL_API swell_status swell_replay_finish(swell_replay* replay);
/* Copies the height field (metres, cache y) into `heights`; `count` must be
 * cells_x * cells_z. */
SWELL_API swell_status swell_replay_heights(swell_replay* replay, float* heights, size_t count);
/* Heights at `count` points (x[i], z[i]) in metres: bilinear between cell centres, NaN
 * outside the mesh. For buoyancy and other gameplay queries. */
SWELL_API swell_status swell_replay_sample(swell_replay* replay, const double* x, const double* z,
                                           size_t count, double* heights);
/* The splash sprites at the current time. `*count` receives how many there are. With
 * out == NULL (and capacity 0) that is all; else up to `capacity` are copied into `out`, and
 * the call returns SWELL_ERROR_BUFFER_SIZE when capacity < *count (the first `capacity` are
 * copied). */
SWELL_API swell_status swell_replay_splashes(swell_replay* replay, swell_splash* out,
                                             size_t capacity, size_t* count);
/* The GL name of the R32F height texture (cells_x x cells_z, linear filtering) in the
 * replay's context, updated by swell_replay_advance. */
SWELL_API swell_status swell_replay_height_texture(swell_replay* replay, unsigned* texture);

#ifdef __cplusplus
}
#endif

#endif /* SWELL_SWELL_H */
