#pragma once
// Prescribed motion of a piston wavemaker wall (paper Sec. 3.3.1: "the pushing wall
// periodically moves back and forth in a random manner, maintaining wave motion during
// the entire simulation"). A pure function of time: the solver asks for the velocity,
// the driver for the displacement; no state, so a resumed bake gets the same motion.
// Besides the paper's random motion: a sinusoid (regular waves) and Goring's (1978) single
// stroke that makes a solitary wave, the two validation waves (docs/validation.md, Progressive
// waves and Solitary wave).

#include <cstdint>
#include <string_view>
#include <vector>

namespace swell::bake {

/// How the piston moves.
enum class PistonKind {
    Sinusoidal, ///< X(t) = S/2 sin(2 pi t / T): regular waves (validation)
    Random,     ///< back-and-forth cycles of seeded random period and stroke (surging wave)
    /// One forward stroke that makes a solitary wave of height H in water of depth h (Goring
    /// 1978): validation of a nonlinear wave that travels without changing shape.
    Solitary,
};
/// Scene-file name of a kind: "sinusoidal", "random", "solitary".
std::string_view toString(PistonKind kind);

struct PistonParams {
    PistonKind kind = PistonKind::Random;
    double period = 1.0;     ///< T (s), Sinusoidal
    double stroke = 0.1;     ///< S, full stroke (m), Sinusoidal
    double periodMin = 0.8;  ///< shortest cycle (s), Random
    double periodMax = 1.6;  ///< longest cycle (s), Random
    double strokeMin = 0.05; ///< smallest full stroke (m), Random
    double strokeMax = 0.15; ///< largest full stroke (m), Random
    double rampTime = 1.0;   ///< the motion is faded in over this time (s), 0 = none
    std::uint64_t seed = 1;  ///< seed of the random cycles
    double height = 0.02;    ///< H, the solitary wave's height above still water (m), Solitary
    double depth = 0.0;      ///< h, still-water depth (m), Solitary: set from the scene's water
    double gravity = 9.81;   ///< g (m/s^2), Solitary: set from the scene's physics
};

/// The solitary wave of Boussinesq's first-order theory, eta = H sech^2(k (x - c t)), that
/// Goring's stroke makes.
struct SolitaryWaveShape {
    double wavenumber = 0.0; ///< k = sqrt(3 H / (4 h^3)) (1/m)
    double celerity = 0.0;   ///< c = sqrt(g (h + H)) (m/s, Rayleigh 1876)
};
/// Throws std::invalid_argument for a non-positive height, depth or gravity.
SolitaryWaveShape solitaryWaveShape(double height, double depth, double gravity);

/// Goring's stroke starts and ends where eta / H = sech^2(theta) = sech^2(4) (1.3e-3):
/// theta = k (c t - X) - 4 runs from -4 to 4 over the stroke.
inline constexpr double kSolitaryHalfWidth = 4.0;

/// The largest solitary wave: H / h = 0.78 (McCowan 1894); a higher one breaks.
inline constexpr double kSolitaryMaxHeightOverDepth = 0.78;

/// Displacement (m, along +x from the rest position) and velocity (m/s) at time t.
struct PistonState {
    double displacement = 0.0;
    double velocity = 0.0;
};

/// The piston's motion. Random cycles each start and end at rest at the rest position:
/// X(t) = S_i/2 (1 - cos(2 pi (t - t_i) / T_i)), so position and velocity are continuous
/// at every cycle boundary. The ramp multiplies by r(t) = (1 - cos(pi t / t_ramp)) / 2,
/// which makes position, velocity and acceleration start from zero.
/// Solitary (Goring 1978): the piston moves with the depth-averaged velocity of the wave's water,
/// dX/dt = c eta(X, t) / (h + eta(X, t)), eta(x, t) = H sech^2(k (c t - x) - 4), from X = 0
/// until theta = 4, then rests at its full stroke S (about sqrt(16 H h / 3)); no ramp (it starts
/// from 1.3e-3 of its largest velocity). The stroke is integrated once (RK4, 4,000 steps) and
/// read back by cubic Hermite interpolation.
/// Most random cycles a piston draws (end_time / period_min): a bound on the memory and time
/// PistonMotion takes; a scene past it is refused naming piston.period_min.
inline constexpr long kMaxPistonCycles = 1'000'000;

class PistonMotion {
public:
    /// Validates (throws std::invalid_argument naming the field) and draws the cycles
    /// needed up to `endTime` (s).
    PistonMotion(const PistonParams& params, double endTime);

    PistonState at(double t) const;
    const PistonParams& params() const { return m_params; }
    /// Start time, period and stroke of each random cycle (empty for Sinusoidal).
    struct Cycle {
        double start, period, stroke;
    };
    const std::vector<Cycle>& cycles() const { return m_cycles; }
    /// The time the stroke ends (s): Solitary only, 0 otherwise.
    double strokeEnd() const { return m_table.empty() ? 0.0 : m_table.back().t; }

private:
    PistonParams m_params;
    std::vector<Cycle> m_cycles;
    struct Sample {
        double t, displacement, velocity;
    };
    std::vector<Sample> m_table; // Solitary: the integrated stroke, evenly spaced in t
};

} // namespace swell::bake
