/* swell-capi-bench: the C API's replay speed, timed like swell-play bench (advance and wait
 * for the GPU, every frame), and the cost of point queries (docs/BENCHMARKS.md). One JSON object
 * on stdout.
 *   swell-capi-bench CACHE [CELLS [FRAMES [POINTS]]]   (defaults: auto, 300, 1000) */
#define _POSIX_C_SOURCE 199309L
#include "swell/swell.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1e3 * (double)t.tv_sec + 1e-6 * (double)t.tv_nsec;
}

/* The exit statuses of every swell program (README "Exit statuses"; cache/cli/exit_codes.h). */
enum { kExitFailed = 1, kExitBadInput = 2, kExitBadCache = 4 };

static int g_exit = 0; /* the status of the first failed call */

static int check(swell_status s, const char* what) {
    if (s != SWELL_OK) {
        fprintf(stderr, "swell-capi-bench: %s: %s\n", what, swell_last_error());
        g_exit = s == SWELL_ERROR_CACHE              ? kExitBadCache
                 : s == SWELL_ERROR_INVALID_ARGUMENT ? kExitBadInput
                                                     : kExitFailed;
        return 0;
    }
    return 1;
}

static const char* const kUsage =
    "usage: swell-capi-bench CACHE [CELLS [FRAMES [POINTS]]]\n"
    "  Times the C API on CACHE: replay creation, frames per second at CELLS x CELLS (0: the\n"
    "  replay's default grid; at most 8192) over FRAMES frames (1..1000000), and POINTS point\n"
    "  queries per frame (1..10000000).\n";

/* argv[index] as an integer in [lo, hi], or `fallback` where it is not given; -1 (after one
 * line naming the argument as typed) where it is not such an integer. */
static long argument(int argc, char** argv, int index, const char* name, long fallback, long lo,
                     long hi) {
    if (index >= argc)
        return fallback;
    char* end = NULL;
    const long v = strtol(argv[index], &end, 10);
    if (end == argv[index] || *end != '\0' || v < lo || v > hi) {
        fprintf(stderr, "swell-capi-bench: %s '%s': not an integer in [%ld, %ld] (see --help)\n",
                name, argv[index], lo, hi);
        return -1;
    }
    return v;
}

int main(int argc, char** argv) {
    if (argc >= 2 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
        fputs(kUsage, stdout);
        return 0;
    }
    if (argc < 2 || argc > 5) {
        fputs(kUsage, stderr);
        return kExitBadInput;
    }
    const long cells = argument(argc, argv, 2, "CELLS", 0, 0, 8192);
    const long frames = argument(argc, argv, 3, "FRAMES", 300, 1, 1000000);
    const long points = argument(argc, argv, 4, "POINTS", 1000, 1, 10000000);
    const int warmup = 10;
    if (cells < 0 || frames < 0 || points < 0)
        return kExitBadInput;
    swell_cache* cache = NULL;
    swell_replay* replay = NULL;
    if (!check(swell_cache_open(argv[1], &cache), "open"))
        return g_exit;
    swell_replay_config config;
    swell_replay_config_default(&config);
    config.cells_x = config.cells_z = (int)cells;
    double t0 = now_ms();
    if (!check(swell_replay_create(cache, &config, &replay), "create"))
        return g_exit;
    const double create_ms = now_ms() - t0;
    swell_grid grid;
    swell_replay_grid(replay, &grid);

    /* Frames at 30 per simulated second, as swell-play bench: advance + wait. */
    double frame_ms = 0.0;
    for (int i = 0; i < warmup + frames; ++i) {
        t0 = now_ms();
        if (!check(swell_replay_advance(replay, i / 30.0), "advance") ||
            !check(swell_replay_finish(replay), "finish"))
            return g_exit;
        if (i >= warmup)
            frame_ms += now_ms() - t0;
    }

    /* Point queries: POINTS spread over the mesh; the first call after an advance reads the
     * field back from the GPU, later calls only interpolate. */
    double* x = malloc(sizeof(double) * (size_t)points);
    double* z = malloc(sizeof(double) * (size_t)points);
    double* h = malloc(sizeof(double) * (size_t)points);
    if (x == NULL || z == NULL || h == NULL) {
        fprintf(stderr, "swell-capi-bench: out of memory for %ld points\n", points);
        return kExitFailed;
    }
    unsigned state = 12345u;
    for (int i = 0; i < points; ++i) {
        state = state * 1664525u + 1013904223u;
        x[i] = grid.x0 + grid.cells_x * grid.dx * (double)(state >> 8) / 16777216.0;
        state = state * 1664525u + 1013904223u;
        z[i] = grid.extent_z * (double)(state >> 8) / 16777216.0;
    }
    const int rounds = 200;
    double first_ms = 0.0, again_ms = 0.0;
    for (int r = 0; r < rounds; ++r) {
        if (!check(swell_replay_advance(replay, r / 30.0), "advance") ||
            !check(swell_replay_finish(replay), "finish"))
            return g_exit;
        t0 = now_ms();
        if (!check(swell_replay_sample(replay, x, z, (size_t)points, h), "sample"))
            return g_exit;
        first_ms += now_ms() - t0;
        t0 = now_ms();
        if (!check(swell_replay_sample(replay, x, z, (size_t)points, h), "sample"))
            return g_exit;
        again_ms += now_ms() - t0;
    }
    printf("{\"cache\": \"%s\", \"cells\": [%d, %d], \"frames\": %d, \"create_ms\": %.1f, "
           "\"fps\": %.2f, \"frame_ms\": %.4f, \"points\": %d, "
           "\"query_us_per_point\": %.5f, \"query_with_readback_us_per_point\": %.5f}\n",
           argv[1], grid.cells_x, grid.cells_z, (int)frames, create_ms, 1e3 * frames / frame_ms,
           frame_ms / frames, (int)points, 1e3 * again_ms / rounds / points,
           1e3 * first_ms / rounds / points);
    free(x);
    free(z);
    free(h);
    swell_replay_destroy(replay);
    swell_cache_close(cache);
    return 0;
}
