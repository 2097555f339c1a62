#pragma once
// What decides whether a checkpoint may be resumed by another build of swell-bake
// (docs/scenes.md, "Checkpoints"): the version of the solver's numerics, which changes
// whenever the solver's results change. The OpenMP thread count never changes them: every loop
// of the solver either writes each particle's own values (gather form) or reduces with an
// exact operation (integer count, min, max), and the floating-point sums of the pressure solve
// (its v.Av and dot products) run in index order on one thread (pressure_solver.cpp), so a
// bake gives the same bits with any --threads and may be resumed with another
// (tests/bake/mps_solver_test.cpp). A rebuild that leaves the numerics alone (help text, I/O,
// a new compiler flag elsewhere) keeps the version, so a long bake can be resumed across an
// upgrade.

namespace swell::bake {

/// Bump whenever the solver's results change (anything that moves a particle, by one bit or
/// more, in tests/bake/numerics_version_test.cpp, which then fails and names the new digest to
/// record). Recorded in checkpoints and in the cache metadata ("numerics_version").
// 3: sub-steps (solver.substep_courant); 4: the default scheme's packing factor (re_packing);
// 5: the default scheme's damping against the shift (solver.shift_damping).
inline constexpr int kNumericsVersion = 5;

} // namespace swell::bake
