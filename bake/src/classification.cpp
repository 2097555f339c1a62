#include "swell/bake/classification.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace swell::bake {

ClassifiedFrame classifyParticles(const Particles& P, double n0, double d1, double d2,
                                  std::span<const std::uint8_t> layer) {
    ClassifiedFrame out;
    std::vector<std::pair<double, double>> surface;
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] != ParticleKind::Water)
            continue;
        WaterClass c = classifyWater(P.n[i], n0, d1, d2); // eq. (4)
        if (c == WaterClass::Deep && !layer.empty() && layer[i])
            c = WaterClass::Surface;
        switch (c) {
        case WaterClass::Splash:
            out.frame.splash.insert(out.frame.splash.end(),
                                    {static_cast<float>(P.x[i]), static_cast<float>(P.y[i]),
                                     static_cast<float>(P.vx[i]), static_cast<float>(P.vy[i])});
            break;
        case WaterClass::Surface:
            surface.emplace_back(P.x[i], P.y[i]);
            break;
        case WaterClass::Deep:
            ++out.deep;
            break;
        }
    }
    std::sort(surface.begin(), surface.end());
    out.frame.surface.reserve(2 * surface.size());
    for (const auto& [x, y] : surface) {
        out.frame.surface.push_back(static_cast<float>(x));
        out.frame.surface.push_back(static_cast<float>(y));
    }
    return out;
}

} // namespace swell::bake
