#include "swell/bake/wave_theory.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace swell::bake {

double dispersionWavenumber(double omega, double depth, double gravity) {
    if (!(omega > 0.0) || !(depth > 0.0) || !(gravity > 0.0))
        throw std::invalid_argument("dispersionWavenumber: omega, depth and g must be positive");
    // Solve f(x) = x tanh(x) - w2h/g = 0 for x = k h; start from Eckart's approximation.
    const double y = omega * omega * depth / gravity;
    double x = y / std::sqrt(std::tanh(y));
    for (int i = 0; i < 100; ++i) {
        const double t = std::tanh(x);
        const double f = x * t - y;
        const double df = t + x * (1.0 - t * t);
        const double step = f / df;
        x -= step;
        if (std::fabs(step) <= 1e-14 * x)
            break;
    }
    return x / depth;
}

double groupVelocity(double omega, double depth, double gravity) {
    const double k = dispersionWavenumber(omega, depth, gravity);
    const double kh2 = 2.0 * k * depth;
    // 2kh / sinh 2kh -> 1 as kh -> 0; above 700, sinh overflows to inf and the ratio is 0.
    const double ratio = kh2 < 1e-8 ? 1.0 : kh2 / std::sinh(kh2);
    return 0.5 * (omega / k) * (1.0 + ratio);
}

double pistonHeightOverStroke(double kh) {
    const double k2 = 2.0 * kh;
    return 2.0 * (std::cosh(k2) - 1.0) / (std::sinh(k2) + k2);
}

double micheLimitSteepness(double kh) {
    return 0.142 * std::tanh(kh);
}

LinearPistonWave linearPistonWave(double stroke, double period, double depth, double gravity) {
    if (!(period > 0.0))
        throw std::invalid_argument("linearPistonWave: period must be positive");
    LinearPistonWave w;
    w.wavenumber = dispersionWavenumber(2.0 * std::numbers::pi / period, depth, gravity);
    w.wavelength = 2.0 * std::numbers::pi / w.wavenumber;
    w.kh = w.wavenumber * depth;
    w.height = stroke * pistonHeightOverStroke(w.kh);
    w.steepness = w.height / w.wavelength;
    w.breakingSteepness = micheLimitSteepness(w.kh);
    return w;
}

} // namespace swell::bake
