// The same replay as heights.c through the C++ libraries (swell::runtime::Playback).
// Usage: heights_cpp CACHE.swell [SEED]
#include <swell/cache/reader.h>
#include <swell/runtime/gl/egl_context.h>
#include <swell/runtime/playback.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

int main(int argc, char** argv) try {
    if (argc < 2) {
        std::fprintf(stderr, "usage: heights_cpp CACHE.swell [SEED]\n");
        return 2;
    }
    const swell::cache::Reader reader(argv[1]);
    const swell::runtime::EglContext context; // headless; current on this thread
    swell::runtime::PlaybackConfig config;
    config.params.cellsX = config.params.cellsZ = 0; // auto, as the C API's default
    config.params.seed = argc > 2 ? std::stoull(argv[2]) : 1;
    swell::runtime::Playback playback(reader, config);
    const swell::runtime::Grid& g = playback.grid();
    const std::vector<double> x{g.x0 + 0.5 * g.cellsX * g.dx}, z{0.5 * g.extentZ};
    std::vector<double> under(1);
    for (int frame = 0; frame < 10; ++frame) {
        playback.advance(frame / 30.0);
        double mean = 0.0;
        for (double h : playback.heights().heights)
            mean += static_cast<float>(h) / static_cast<double>(g.cellsX * g.cellsZ);
        playback.sample(x, z, under);
        std::printf("frame %d: %dx%d mean %.6f m, at (%.3f, %.3f) %.6f m\n", frame, g.cellsX,
                    g.cellsZ, mean, x[0], z[0], under[0]);
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "heights_cpp: %s\n", e.what());
    return 1;
}
