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

static int check(swell_status s, const char* what) {
    if (s != SWELL_OK) {
        fprintf(stderr, "swell-capi-bench: %s: %s\n", what, swell_last_error());
        return 0;
    }
    return 1;
}

static const char* const kUsage =
    "usage: swell-capi-bench CACHE [CELLS [FRAMES [POINTS]]]\n"
    "  Times the C API on CACHE: replay creation, frames per second at CELLS x CELLS (0: the\n"
    "  replay's default grid) over FRAMES frames, and POINTS point queries per frame.\n";

int main(int argc, char** argv) {
    if (argc >= 2 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
        fputs(kUsage, stdout);
        return 0;
    }
    if (argc < 2) {
        fputs(kUsage, stderr);
        return 2;
    }
    const int cells = argc > 2 ? atoi(argv[2]) : 0;
    const int frames = argc > 3 ? atoi(argv[3]) : 300;
    const int points = argc > 4 ? atoi(argv[4]) : 1000;
    const int warmup = 10;
    if (cells < 0 || frames < 1 || points < 1) {
        fprintf(stderr, "swell-capi-bench: CELLS >= 0, FRAMES >= 1, POINTS >= 1\n");
        return 2;
    }
    swell_cache* cache = NULL;
    swell_replay* replay = NULL;
    if (!check(swell_cache_open(argv[1], &cache), "open"))
        return 1;
    swell_replay_config config;
    swell_replay_config_default(&config);
    config.cells_x = config.cells_z = cells;
    double t0 = now_ms();
    if (!check(swell_replay_create(cache, &config, &replay), "create"))
        return 1;
    const double create_ms = now_ms() - t0;
    swell_grid grid;
    swell_replay_grid(replay, &grid);

    /* Frames at 30 per simulated second, as swell-play bench: advance + wait. */
    double frame_ms = 0.0;
    for (int i = 0; i < warmup + frames; ++i) {
        t0 = now_ms();
        if (!check(swell_replay_advance(replay, i / 30.0), "advance") ||
            !check(swell_replay_finish(replay), "finish"))
            return 1;
        if (i >= warmup)
            frame_ms += now_ms() - t0;
    }

    /* Point queries: POINTS spread over the mesh; the first call after an advance reads the
     * field back from the GPU, later calls only interpolate. */
    double* x = malloc(sizeof(double) * (size_t)points);
    double* z = malloc(sizeof(double) * (size_t)points);
    double* h = malloc(sizeof(double) * (size_t)points);
    if (x == NULL || z == NULL || h == NULL)
        return 1;
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
            return 1;
        t0 = now_ms();
        if (!check(swell_replay_sample(replay, x, z, (size_t)points, h), "sample"))
            return 1;
        first_ms += now_ms() - t0;
        t0 = now_ms();
        if (!check(swell_replay_sample(replay, x, z, (size_t)points, h), "sample"))
            return 1;
        again_ms += now_ms() - t0;
    }
    printf("{\"cache\": \"%s\", \"cells\": [%d, %d], \"frames\": %d, \"create_ms\": %.1f, "
           "\"fps\": %.2f, \"frame_ms\": %.4f, \"points\": %d, "
           "\"query_us_per_point\": %.5f, \"query_with_readback_us_per_point\": %.5f}\n",
           argv[1], grid.cells_x, grid.cells_z, frames, create_ms, 1e3 * frames / frame_ms,
           frame_ms / frames, points, 1e3 * again_ms / rounds / points,
           1e3 * first_ms / rounds / points);
    free(x);
    free(z);
    free(h);
    swell_replay_destroy(replay);
    swell_cache_close(cache);
    return 0;
}
