#pragma once
// What decides whether a checkpoint may be resumed by another build of swell-bake
// (docs/scenes.md, "Checkpoints"): the version of the solver's numerics, which changes
// whenever the solver's results change, and whether the OpenMP thread count changes them.
// A rebuild that leaves the numerics alone (help text, I/O, a new compiler flag elsewhere)
// keeps the version, so a long bake can be resumed across an upgrade.

#include <cstddef>

namespace swell::bake {

/// Bump whenever the solver's results change (anything that moves a particle, by one bit or
/// more, in tests/bake/numerics_version_test.cpp, which then fails and names the new digest to
/// record). Recorded in checkpoints and in the cache metadata ("numerics_version").
inline constexpr int kNumericsVersion = 2;

/// True when a scene of `particles` particles (water + fixed) gives results that depend on
/// the OpenMP thread count: the solver's floating-point reductions (the PPE matrix-vector
/// product's vAv, the conjugate gradient's dot products) run in parallel, and so sum in a
/// thread-dependent order, only from kParallelMin = 4096 rows (parallel_thresholds.h), and
/// the PPE never has more rows than particles. Below that the thread count is irrelevant.
bool threadCountAffectsResults(std::size_t particles);

} // namespace swell::bake
