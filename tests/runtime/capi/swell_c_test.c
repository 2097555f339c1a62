/* The C API (swell.h) from C: a replay of a synthetic cache, and every kind of bad input across
 * the boundary (null handles, a damaged cache, wrong buffer sizes, parameters out of range)
 * gives its status and a message naming the problem. Compiled as C99.
 *   swell_c_test GOOD.swell DAMAGED.swell */
#include "swell/swell.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;

#define EXPECT(cond)                                                                               \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "%s:%d: expected %s (last error: %s)\n", __FILE__, __LINE__, #cond,    \
                    swell_last_error());                                                           \
            ++failures;                                                                            \
        }                                                                                          \
    } while (0)

/* The call fails with `status` and its message contains `needle`. */
#define EXPECT_ERROR(call, status, needle)                                                         \
    do {                                                                                           \
        swell_status s_ = (call);                                                                  \
        if (s_ != (status) || strstr(swell_last_error(), (needle)) == NULL) {                      \
            fprintf(stderr, "%s:%d: %s gave %s '%s', expected %s with '%s'\n", __FILE__, __LINE__, \
                    #call, swell_status_name(s_), swell_last_error(), swell_status_name(status),   \
                    (needle));                                                                     \
            ++failures;                                                                            \
        }                                                                                          \
    } while (0)

static swell_replay* make(const swell_cache* cache, int cells, uint64_t seed, const char* json) {
    swell_replay_config c;
    swell_replay_config_default(&c);
    c.cells_x = c.cells_z = cells;
    c.seed = seed;
    c.params_json = json;
    swell_replay* r = NULL;
    EXPECT(swell_replay_create(cache, &c, &r) == SWELL_OK);
    EXPECT(r != NULL);
    return r;
}

static void test_errors_without_a_replay(const char* damaged) {
    swell_cache* cache = (swell_cache*)0x1;
    EXPECT(strlen(swell_version()) > 0);
    EXPECT(strcmp(swell_status_name(SWELL_ERROR_BUFFER_SIZE), "wrong buffer size") == 0);
    EXPECT_ERROR(swell_cache_open("/nonexistent/x.swell", &cache), SWELL_ERROR_CACHE,
                 "/nonexistent/x.swell");
    EXPECT(cache == NULL); /* *out is cleared on failure */
    EXPECT_ERROR(swell_cache_open(damaged, &cache), SWELL_ERROR_CACHE, damaged);
    EXPECT_ERROR(swell_cache_open(NULL, &cache), SWELL_ERROR_INVALID_ARGUMENT, "path is NULL");
    EXPECT_ERROR(swell_cache_open(damaged, NULL), SWELL_ERROR_INVALID_ARGUMENT, "out is NULL");
    swell_cache_info info;
    EXPECT_ERROR(swell_cache_info_get(NULL, &info), SWELL_ERROR_INVALID_ARGUMENT, "cache");
    swell_replay_config c;
    swell_replay_config_default(&c);
    swell_replay* r = NULL;
    EXPECT_ERROR(swell_replay_create(NULL, &c, &r), SWELL_ERROR_INVALID_ARGUMENT, "cache is NULL");
    float h[4];
    double x = 0.0, y = 0.0;
    size_t n = 0;
    unsigned tex = 0;
    swell_grid g;
    EXPECT_ERROR(swell_replay_advance(NULL, 0.0), SWELL_ERROR_INVALID_ARGUMENT, "replay is NULL");
    EXPECT_ERROR(swell_replay_heights(NULL, h, 4), SWELL_ERROR_INVALID_ARGUMENT, "replay");
    EXPECT_ERROR(swell_replay_sample(NULL, &x, &x, 1, &y), SWELL_ERROR_INVALID_ARGUMENT, "replay");
    EXPECT_ERROR(swell_replay_splashes(NULL, NULL, 0, &n), SWELL_ERROR_INVALID_ARGUMENT, "replay");
    EXPECT_ERROR(swell_replay_height_texture(NULL, &tex), SWELL_ERROR_INVALID_ARGUMENT, "replay");
    EXPECT_ERROR(swell_replay_grid(NULL, &g), SWELL_ERROR_INVALID_ARGUMENT, "replay");
    EXPECT_ERROR(swell_replay_finish(NULL), SWELL_ERROR_INVALID_ARGUMENT, "replay");
    swell_replay_destroy(NULL);
    swell_cache_close(NULL);
}

static void test_bad_parameters(const swell_cache* cache) {
    swell_replay_config c;
    swell_replay* r = (swell_replay*)0x1;
    swell_replay_config_default(&c);
    c.slices = -3;
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT, "slices");
    EXPECT(r == NULL);
    swell_replay_config_default(&c);
    c.fluctuation = 1.5;
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT, "fluctuation must be in [0, 1]");
    swell_replay_config_default(&c);
    c.cells_x = 32; /* cells_z left at 0 */
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT, "cells_z");
    swell_replay_config_default(&c);
    c.mode = (swell_mode)7;
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT, "config.mode");
    swell_replay_config_default(&c);
    c.context = (swell_context)5;
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT,
                 "config.context");
    swell_replay_config_default(&c);
    c.params_json = "{\"params\": {";
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT, "params_json");
    c.params_json = "{\"params\": {\"sigma\": 0.01}}";
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT, "sigma");
    c.params_json = "{\"params\": {\"seed\": 3}}";
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT,
                 "set seed in swell_replay_config");
    c.params_json = "{\"colour\": 1}";
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT,
                 "unknown key colour");
    c.params_json = "{\"splash\": {\"artificial_per_real\": -1}}";
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT, "artificial");
    c.params_json = "{\"memory_budget_gib\": 1e-6}";
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT,
                 "above the memory budget");
    c.params_json = "[1, 2]";
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_INVALID_ARGUMENT, "JSON object");
    /* The caller's context was asked for, and none is current on this thread. */
    swell_replay_config_default(&c);
    c.context = SWELL_CONTEXT_CURRENT;
    EXPECT_ERROR(swell_replay_create(cache, &c, &r), SWELL_ERROR_GL, "no GL context is current");
}

static void test_replay(const swell_cache* cache) {
    swell_cache_info info;
    EXPECT(swell_cache_info_get(cache, &info) == SWELL_OK);
    EXPECT(info.frame_count == 200);
    EXPECT(info.frame_seconds > 0.0);
    EXPECT(info.particle_spacing > 0.0);

    swell_replay* r = make(cache, 32, 7, NULL);
    swell_grid g;
    EXPECT(swell_replay_grid(r, &g) == SWELL_OK);
    EXPECT(g.cells_x == 32 && g.cells_z == 32);
    EXPECT(fabs(g.extent_z - g.cells_z * g.dz) < 1e-9);
    const size_t cells = (size_t)g.cells_x * (size_t)g.cells_z;
    float* h = malloc(sizeof(float) * cells);
    float* h2 = malloc(sizeof(float) * cells);
    EXPECT(h != NULL && h2 != NULL);

    EXPECT(swell_replay_advance(r, 0.5) == SWELL_OK);
    EXPECT_ERROR(swell_replay_heights(r, h, cells - 1), SWELL_ERROR_BUFFER_SIZE, "32 x 32");
    EXPECT_ERROR(swell_replay_heights(r, NULL, cells), SWELL_ERROR_INVALID_ARGUMENT, "heights");
    EXPECT_ERROR(swell_replay_advance(r, NAN), SWELL_ERROR_INVALID_ARGUMENT, "finite");
    EXPECT(swell_replay_advance(r, 0.5) == SWELL_OK);
    EXPECT(swell_replay_heights(r, h, cells) == SWELL_OK);
    EXPECT(strcmp(swell_last_error(), "") == 0); /* success clears the message */
    double lo = 1e30, hi = -1e30;
    for (size_t i = 0; i < cells; ++i) {
        EXPECT(isfinite(h[i]));
        lo = h[i] < lo ? h[i] : lo;
        hi = h[i] > hi ? h[i] : hi;
    }
    EXPECT(lo >= info.y_min && hi <= info.y_max);
    EXPECT(hi - lo > 0.01); /* a wave, not a flat field */

    /* Point queries at the cell centres give the cells' heights; outside the mesh, NaN. */
    double x[3], z[3], y[3];
    x[0] = g.x0 + 0.5 * g.dx;
    z[0] = 0.5 * g.dz;
    x[1] = g.x0 + 10.5 * g.dx;
    z[1] = 20.5 * g.dz;
    x[2] = g.x0 - 1.0;
    z[2] = 0.5;
    EXPECT(swell_replay_sample(r, x, z, 3, y) == SWELL_OK);
    EXPECT(fabs(y[0] - h[0]) < 1e-6);
    EXPECT(fabs(y[1] - h[20 * 32 + 10]) < 1e-6);
    EXPECT(isnan(y[2]));
    EXPECT(swell_replay_sample(r, NULL, NULL, 0, NULL) == SWELL_OK);
    EXPECT_ERROR(swell_replay_sample(r, x, NULL, 3, y), SWELL_ERROR_INVALID_ARGUMENT, "z is NULL");

    /* Splashes: ask for the count, then too small a buffer, then enough. */
    size_t count = 0;
    EXPECT(swell_replay_splashes(r, NULL, 0, &count) == SWELL_OK);
    EXPECT(count > 0);
    swell_splash one;
    size_t again = 0;
    EXPECT_ERROR(swell_replay_splashes(r, &one, 1, &again), SWELL_ERROR_BUFFER_SIZE, "sprites");
    EXPECT(again == count);
    swell_splash* sprites = malloc(sizeof(swell_splash) * count);
    EXPECT(swell_replay_splashes(r, sprites, count, &again) == SWELL_OK);
    for (size_t i = 0; i < count; ++i)
        EXPECT(sprites[i].alpha >= 0.0f && sprites[i].alpha <= 1.0f && isfinite(sprites[i].y));
    free(sprites);

    unsigned tex = 0;
    EXPECT(swell_replay_height_texture(r, &tex) == SWELL_OK);
    EXPECT(tex != 0);

    /* Same seed, same surface; another seed, another one (F > 0). */
    swell_replay* same = make(cache, 32, 7, NULL);
    swell_replay* other = make(cache, 32, 8, NULL);
    EXPECT(swell_replay_advance(same, 0.5) == SWELL_OK);
    EXPECT(swell_replay_heights(same, h2, cells) == SWELL_OK);
    EXPECT(memcmp(h, h2, sizeof(float) * cells) == 0);
    EXPECT(swell_replay_advance(other, 0.5) == SWELL_OK);
    EXPECT(swell_replay_heights(other, h2, cells) == SWELL_OK);
    EXPECT(memcmp(h, h2, sizeof(float) * cells) != 0);
    swell_replay_destroy(same);
    swell_replay_destroy(other);

    /* The other layouts run too. */
    swell_replay_config c;
    swell_replay_config_default(&c);
    c.cells_x = c.cells_z = 32;
    c.mode = SWELL_MODE_RIPPLE;
    c.params_json = "{\"ripple\": {\"angles_degrees\": [0, 45]}}";
    swell_replay* ripple = NULL;
    EXPECT(swell_replay_create(cache, &c, &ripple) == SWELL_OK);
    EXPECT(swell_replay_advance(ripple, 1.0) == SWELL_OK);
    EXPECT(swell_replay_heights(ripple, h2, cells) == SWELL_OK);
    swell_replay_destroy(ripple);

    free(h);
    free(h2);
    swell_replay_destroy(r);
}

int main(int argc, char** argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: swell_c_test GOOD.swell DAMAGED.swell\n");
        return 2;
    }
    test_errors_without_a_replay(argv[2]);
    swell_cache* cache = NULL;
    if (swell_cache_open(argv[1], &cache) != SWELL_OK) {
        fprintf(stderr, "cannot open %s: %s\n", argv[1], swell_last_error());
        return 1;
    }
    test_bad_parameters(cache);
    test_replay(cache);
    swell_cache_close(cache);
    if (failures > 0) {
        fprintf(stderr, "swell_c_test: %d failures\n", failures);
        return 1;
    }
    printf("swell_c_test: all passed\n");
    return 0;
}
