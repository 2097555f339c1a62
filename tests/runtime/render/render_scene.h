#pragma once
// The grid and domain the render tests draw (camera, water renderer): 64 x 48 cells over a
// 4.4 m wide domain, 32 slices.

#include "swell/cache/header.h"
#include "swell/runtime/replay/replay_params.h"

namespace swell::runtime::test {

inline Grid renderGrid() {
    Grid g;
    g.cellsX = 64;
    g.cellsZ = 48;
    g.slices = 32;
    g.x0 = -0.2;
    g.dx = 4.4 / 64;
    g.dz = g.dx;
    g.extentZ = 48 * g.dz;
    return g;
}

inline const cache::Domain kRenderDomain{-0.2f, 0.0f, 4.2f, 0.9f};

} // namespace swell::runtime::test
