#pragma once
// Prescribed motion of a piston wavemaker wall (paper Sec. 3.3.1: "the pushing wall
// periodically moves back and forth in a random manner, maintaining wave motion during
// the entire simulation"). A pure function of time: the solver asks for the velocity,
// the driver for the displacement; no state, so a resumed bake gets the same motion.

#include <cstdint>
#include <string_view>
#include <vector>

namespace swell::bake {

/// How the piston moves.
enum class PistonKind {
    Sinusoidal, ///< X(t) = S/2 sin(2 pi t / T): regular waves (validation)
    Random,     ///< back-and-forth cycles of seeded random period and stroke (surging wave)
};
/// Scene-file name of a kind: "sinusoidal", "random".
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
};

/// Displacement (m, along +x from the rest position) and velocity (m/s) at time t.
struct PistonState {
    double displacement = 0.0;
    double velocity = 0.0;
};

/// The piston's motion. Random cycles each start and end at rest at the rest position:
/// X(t) = S_i/2 (1 - cos(2 pi (t - t_i) / T_i)), so position and velocity are continuous
/// at every cycle boundary. The ramp multiplies by r(t) = (1 - cos(pi t / t_ramp)) / 2,
/// which makes position, velocity and acceleration start from zero.
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

private:
    PistonParams m_params;
    std::vector<Cycle> m_cycles;
};

} // namespace swell::bake
