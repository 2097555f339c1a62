#pragma once
// Linear water-wave theory used to set up and validate wave scenes: the dispersion
// relation, the linear piston-wavemaker transfer function and a breaking limit.

namespace swell::bake {

/// Wavenumber k (1/m) of a linear wave of angular frequency omega (rad/s) in depth h (m):
/// the root of omega^2 = g k tanh(k h) (dispersion relation), by Newton's method to 1e-14
/// relative. Throws std::invalid_argument for non-positive omega, h or g.
double dispersionWavenumber(double omega, double depth, double gravity);

/// Group velocity (m/s) of a linear wave of angular frequency omega (rad/s) in depth h (m):
/// c_g = (c / 2) (1 + 2kh / sinh 2kh), c = omega / k, k from dispersionWavenumber. Tends to
/// c / 2 in deep water and to sqrt(g h) in shallow water. Throws like dispersionWavenumber.
double groupVelocity(double omega, double depth, double gravity);

/// Piston wavemaker in linear (first-order wavemaker) theory: wave height over stroke,
/// H / S = 2 (cosh 2kh - 1) / (sinh 2kh + 2kh). S is the full stroke (twice the amplitude).
double pistonHeightOverStroke(double kh);

/// Miche (1944) limiting steepness of a progressive wave: H_max / L = 0.142 tanh(k h).
/// A wave steeper than this breaks.
double micheLimitSteepness(double kh);

/// A regular wave made by a sinusoidal piston, predicted by linear theory.
struct LinearPistonWave {
    double wavenumber = 0.0;        ///< k (1/m)
    double wavelength = 0.0;        ///< L = 2 pi / k (m)
    double kh = 0.0;                ///< relative depth (-)
    double height = 0.0;            ///< H = S * pistonHeightOverStroke(kh) (m)
    double steepness = 0.0;         ///< H / L (-)
    double breakingSteepness = 0.0; ///< Miche limit at this kh (-)
    bool breaks() const { return steepness > breakingSteepness; }
};

/// Linear-theory wave of a piston with full stroke `stroke` (m) and period `period` (s)
/// in still water of depth `depth` (m).
LinearPistonWave linearPistonWave(double stroke, double period, double depth, double gravity);

} // namespace swell::bake
