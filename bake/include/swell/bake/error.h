#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>

namespace swell::bake {

/// A scene file or scene value that cannot be used. The message names the key
/// (e.g. "solver.dt") and what is wrong with it; an error about the whole file (no key) is
/// the problem alone, which names the file.
class SceneError : public std::invalid_argument {
public:
    SceneError(std::string key, const std::string& problem)
        : std::invalid_argument(key.empty() ? problem : "scene key '" + key + "': " + problem),
          m_key(std::move(key)) {}
    /// The dotted key path the error is about ("" for the whole file).
    const std::string& key() const { return m_key; }

private:
    std::string m_key;
};

/// A simulation step that produced an unusable state (NaN/Inf, an unconverged
/// pressure solve, a Courant number above the limit, a particle out of the
/// domain, a neighbour overflow). The run must stop: the state is not trusted.
class DivergenceError : public std::runtime_error {
public:
    DivergenceError(long step, double time, std::size_t particle, const std::string& reason);
    /// Index of the failing step (1 = first step of the run).
    long step() const { return m_step; }
    /// Simulated time (s) the failing step was advancing to.
    double time() const { return m_time; }
    /// Index of the offending particle in the solver's particle arrays.
    std::size_t particle() const { return m_particle; }
    const std::string& reason() const { return m_reason; }

private:
    long m_step;
    double m_time;
    std::size_t m_particle;
    std::string m_reason;
};

} // namespace swell::bake
