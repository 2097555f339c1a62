#pragma once
#include <cstdint>

namespace swell::bake {

/// Class of a water particle by its number density (paper eq. (4)).
enum class WaterClass : std::uint8_t { Splash, Surface, Deep };

/// Paper eq. (4): splash if n < d1 n0, surface if d1 n0 <= n <= d2 n0, deep if n > d2 n0.
inline WaterClass classifyWater(double n, double n0, double d1, double d2) {
    if (n < d1 * n0) return WaterClass::Splash;
    if (n <= d2 * n0) return WaterClass::Surface;
    return WaterClass::Deep;
}

} // namespace swell::bake
