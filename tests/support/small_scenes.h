#pragma once
// Small scenes built in code for the solver's unit tests: fast enough to step many times in
// a test, with nothing read from disk.

#include "swell/bake/scene.h"

namespace swell::test {

/// A 0.1 m x 0.2 m water column at the left of a 0.4 m x 0.3 m tank, l0 = 1 cm (200 water
/// particles), 1 ms steps, the textbook scheme (the reference these tests' figures are of);
/// everything else the defaults.
inline bake::Scene smallDamBreak() {
    bake::Scene s;
    s.solver = bake::schemeParams(bake::Scheme::Textbook);
    s.geometry.particleSpacing = 0.01;
    s.geometry.tank = bake::Box{0.0, 0.0, 0.4, 0.3};
    s.geometry.water = {bake::Box{0.0, 0.0, 0.1, 0.2}};
    s.solver.time.dt = 0.001;
    return s;
}

} // namespace swell::test
