#pragma once
// Splash sprites in the ripple and whirlpool layouts. SplashSystem lays splashes out on the
// surging slice set (Sec. 5: x along the slice, at the real slice's z); the other replay modes
// put that slice set elsewhere (docs/runtime.md), and the sprites follow it:
//  * ripple direction d (Sec. 4.4): the slice set rotated by a_d about the mesh centre
//    C = (x0 + N dx / 2, extentZ / 2): p = C + R(a_d) (q - C) in (x, z);
//  * whirlpool (Sec. 4.5): slice coordinate s = z / dz * 2K / M - 1 (j at a real slice's z),
//    column u = (x - x0) / dx; the point of spiral s at t = 2 pi u / N:
//    r = a e^(b t), angle 2 pi (s + spin(tau)) / J + t about C (whirlpool.h).
// Heights (y) and opacity are kept. Sprites that land outside the mesh's x-z extent (the
// rotated set's corners, the spirals' outer ends beyond the mesh) are dropped: there is no water
// there. Surging: nothing changes.

#include "swell/runtime/modes/mode_params.h"
#include "swell/runtime/render/splash_system.h"
#include "swell/runtime/replay/bake_record.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/slice_sampler.h"

#include <cstdint>
#include <span>
#include <vector>

namespace swell::runtime {

/// Moves `sprites` (laid out by SplashSystem on the surging slice set of `grid`) to the layout
/// of `mode` (ripple: direction `direction`; whirlpool: spin at animation time `tau`; surging:
/// where they are) and drops those outside the mesh: in the surging tank, spray thrown past a
/// wall would fall outside the box, where the simulated tank's walls hold it. Spray outside
/// the grid's own x range (the wave maker's zone, ExtentX::Water) is dropped before the move,
/// so that no mode turns it into a line or ring of sprites inside the mesh. Throws
/// std::invalid_argument for a ripple direction out of range.
/// Reach of the recycling's cut lines, in l0: within it the MPS kernel (r_e = 3.1 l0 for the
/// Laplacian) finds too few neighbours and the bake marks particles as splashes.
inline constexpr double kRecyclingSprayBand = 4.0;

/// A scene with a wave maker's zone (bake_record.h: a recycling channel's inflow, and its
/// outflow at the water's end): the spray shown kept kRecyclingSprayBand l0 inside the shown
/// water range (shownWaterX), away from the inflow zone's end and the outflow, where the
/// recycling itself makes it. Otherwise `params` unchanged.
SplashParams keepSprayAwayFromTheWaveMaker(SplashParams params, const BakeRecord& record);

void placeSplashes(std::vector<SplashSprite>& sprites, const Grid& grid, const ModeParams& mode,
                   int direction, double tau);

/// One SplashSystem per slice set (`sets` of them) over `frames`, slice set d's artificial
/// splashes seeded by a stream of their own derived from the run's `seed` (apart from the set's
/// noise seed, sliceSetSeed), so the same run seed gives the same sprites in every program.
std::vector<SplashSystem> makeSplashSystems(const FrameSet& frames, const Grid& grid,
                                            const SplashParams& params, std::uint64_t seed,
                                            std::size_t sets);

/// The sprites of every slice set at animation time tau (`seconds` of simulated time): each
/// real slice shows the splashes of the cache frame its sampler chooses (the GPU's choice),
/// placed in `mode`'s layout. `systems` and `samplers` have one entry per slice set; nothing
/// when the systems are not active().
std::vector<SplashSprite> modeSplashes(std::span<const SplashSystem> systems,
                                       std::span<const SliceSampler> samplers, const Grid& grid,
                                       const ModeParams& mode, double tau, double seconds);

} // namespace swell::runtime
