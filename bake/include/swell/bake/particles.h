#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace swell::bake {

/// What a particle is. Water moves; Wall particles are fixed and take part in the
/// pressure solve (K&O 1996 "wall particles"); Dummy particles are fixed layers
/// behind the walls that only complete the number density of wall particles.
enum class ParticleKind : std::uint8_t { Water, Wall, Dummy };

std::string_view toString(ParticleKind kind);

/// Particle state as a structure of arrays (index = particle id, stable for the run but for
/// water taken out of it, MpsSolver::removeWater, which moves the later indices down).
struct Particles {
    std::vector<double> x;  ///< position x (m)
    std::vector<double> y;  ///< position y (m), up
    std::vector<double> vx; ///< velocity x (m/s)
    std::vector<double> vy; ///< velocity y (m/s)
    std::vector<double> p;  ///< pressure (Pa), from the last pressure solve
    std::vector<double> n;  ///< particle number density at the last step (dimensionless)
    std::vector<ParticleKind> kind;

    std::size_t size() const { return x.size(); }
    /// Appends a particle at rest with zero pressure.
    void add(double px, double py, ParticleKind k);
    /// Reserves room for `count` particles in every array.
    void reserve(std::size_t count);
    std::size_t count(ParticleKind k) const;
    /// Whether every array has size() entries.
    bool consistent() const;
};

} // namespace swell::bake
