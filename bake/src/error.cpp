#include "swell/bake/error.h"

#include <fmt/format.h>

namespace swell::bake {

DivergenceError::DivergenceError(long step, double time, std::size_t particle,
                                 const std::string& reason)
    : std::runtime_error(
          fmt::format("simulation diverged at step {} (t = {:.6f} s), particle {}: {}", step, time,
                      particle, reason)),
      m_step(step), m_time(time), m_particle(particle), m_reason(reason) {}

} // namespace swell::bake
