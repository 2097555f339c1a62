#pragma once
// The cubic smoothstep, as GLSL's smoothstep(e0, e1, x): 0 below e0, 1 above e1, value and
// slope continuous. The CPU side of the shaders' tapers (ripple weights, the whirlpool's funnel).

#include <algorithm>

namespace swell::runtime {

inline double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

} // namespace swell::runtime
