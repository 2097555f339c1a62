#include "swell/bake/spill.h"

namespace swell::bake {

TankOutline tankOutline(const GeometryParams& g) {
    const double l0 = g.particleSpacing;
    return TankOutline{*g.tank, (g.wallLayers + g.dummyLayers) * l0,
                       static_cast<double>(bedExtensionCells(g)) * l0, l0};
}

std::string_view toString(Escape e) {
    switch (e) {
    case Escape::OverFrontWall:
        return "over the front wall";
    case Escape::OverBackWall:
        return "over the back wall";
    case Escape::OffBedBehind:
        return "off the end of the bed behind the back wall";
    case Escape::ThroughFrontWall:
        return "through the front wall";
    case Escape::ThroughBackWall:
        return "through the back wall";
    case Escape::ThroughBed:
        return "through the bed";
    }
    return "out of the tank";
}

bool spilled(Escape e) {
    return e == Escape::OverFrontWall || e == Escape::OverBackWall || e == Escape::OffBedBehind;
}

std::vector<EscapedWater> findEscapedWater(const Particles& p, const TankOutline& tank) {
    const Box o = tank.outer();
    const double top = o.y1 - tank.spacing; // "over": within one spacing of the top or above
    std::vector<EscapedWater> out;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.kind[i] != ParticleKind::Water)
            continue;
        const double x = p.x[i], y = p.y[i];
        if (x > o.x1) {
            out.push_back({i, y >= top ? Escape::OverFrontWall : Escape::ThroughFrontWall});
        } else if (x < o.x0) {
            // Behind a piston the water may have gone over it and run off the bed's end: the
            // height there says nothing about how it got behind the piston.
            const Escape low =
                tank.bedBehind > 0.0 ? Escape::OffBedBehind : Escape::ThroughBackWall;
            out.push_back({i, y >= top ? Escape::OverBackWall : low});
        } else if (y < o.y0) {
            out.push_back({i, Escape::ThroughBed});
        }
    }
    return out;
}

} // namespace swell::bake
