#pragma once
// Water that leaves an open tank (docs/scenes.md "Spilled water"). A tank (geometry.tank) has no
// lid: spray thrown above a side wall can fly over it and fall outside, as it would from a real
// flume. Such water takes no further part in the flow in the tank, so the bake takes it out of
// the run (MpsSolver::removeWater) and counts it, rather than following it until it leaves the
// domain and stopping there. Water found outside the tank lower than a wall's top went through
// the wall: that is a broken simulation, and the bake stops.

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "swell/bake/box.h"
#include "swell/bake/geometry.h"
#include "swell/bake/particles.h"

namespace swell::bake {

/// The outside of a tank's solid: what water must cross to leave it.
struct TankOutline {
    Box inner;              ///< the water side of the walls and bed (geometry.tank)
    double thickness = 0.0; ///< wall and dummy layers (m)
    double bedBehind = 0.0; ///< bed extension behind the back wall (m, for a piston)
    double spacing = 0.0;   ///< particle spacing l0 (m)

    /// The outer faces: x0 the back wall's (or the end of the bed behind it), x1 the front
    /// wall's, y0 the bed's underside; y1 the walls' top.
    Box outer() const {
        return {inner.x0 - thickness - bedBehind, inner.y0 - thickness, inner.x1 + thickness,
                inner.y1};
    }
};

/// The outline of `geometry`'s tank as generateGeometry lays it out; geometry.tank must be set.
TankOutline tankOutline(const GeometryParams& geometry);

/// How a water particle outside the tank's outline got there.
enum class Escape : std::uint8_t {
    OverFrontWall,    ///< beyond the front wall, no lower than its top
    OverBackWall,     ///< beyond the back wall (or the bed behind it), no lower than its top
    OffBedBehind,     ///< off the end of the bed behind a piston: over or past the piston
    ThroughFrontWall, ///< beyond the front wall, lower than its top
    ThroughBackWall,  ///< beyond the back wall without a bed behind it, lower than its top
    ThroughBed,       ///< below the bed
};

std::string_view toString(Escape e);
/// Whether water that escaped this way spilled (true) or leaked through a solid (false).
bool spilled(Escape e);

struct EscapedWater {
    std::size_t particle = 0;
    Escape route = Escape::OverFrontWall;
};

/// Water particles of `p` outside `tank`'s outline, in index order. A particle counts as over
/// a wall when it is no more than one spacing below the wall's top: checked every step, spray
/// is found within a step of passing the outer face, at about the height it crossed at.
std::vector<EscapedWater> findEscapedWater(const Particles& p, const TankOutline& tank);

} // namespace swell::bake
