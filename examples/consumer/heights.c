/* Replays a cache through swell's C API: the mean height of 10 frames and the height under a
 * floating object at the middle of the mesh. Usage: heights_c CACHE.swell [SEED] */
#include <swell/swell.h>

#include <stdio.h>
#include <stdlib.h>

static int fail(const char* what) {
    fprintf(stderr, "heights_c: %s: %s\n", what, swell_last_error());
    return 1;
}

int main(int argc, char** argv) {
    if (argc < 2)
        return fprintf(stderr, "usage: heights_c CACHE.swell [SEED]\n"), 2;
    swell_cache* cache;
    if (swell_cache_open(argv[1], &cache) != SWELL_OK)
        return fail("open");
    swell_replay_config config;
    swell_replay_config_default(&config); /* surging, auto resolution, headless */
    config.seed = argc > 2 ? strtoull(argv[2], NULL, 10) : 1;
    swell_replay* replay;
    if (swell_replay_create(cache, &config, &replay) != SWELL_OK)
        return fail("create");
    swell_grid grid;
    swell_replay_grid(replay, &grid);
    const size_t cells = (size_t)grid.cells_x * (size_t)grid.cells_z;
    float* heights = malloc(sizeof(float) * cells);
    const double x = grid.x0 + 0.5 * grid.cells_x * grid.dx, z = 0.5 * grid.extent_z;
    for (int frame = 0; frame < 10; ++frame) {
        double under = 0.0, mean = 0.0;
        if (swell_replay_advance(replay, frame / 30.0) != SWELL_OK ||
            swell_replay_heights(replay, heights, cells) != SWELL_OK ||
            swell_replay_sample(replay, &x, &z, 1, &under) != SWELL_OK)
            return fail("frame");
        for (size_t i = 0; i < cells; ++i)
            mean += heights[i] / (double)cells;
        printf("frame %d: %dx%d mean %.6f m, at (%.3f, %.3f) %.6f m\n", frame, grid.cells_x,
               grid.cells_z, mean, x, z, under);
    }
    free(heights);
    swell_replay_destroy(replay);
    swell_cache_close(cache);
    return 0;
}
