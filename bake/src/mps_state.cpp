// MpsSolver::exportState / importState (checkpoint / resume, docs/scenes.md "Checkpoints"). Kept
// apart from the numerics in mps_solver.cpp: plain copies of the state that survives from step to
// step.
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "swell/bake/mps_solver.h"

namespace swell::bake {

MpsState MpsSolver::exportState() const {
    MpsState s;
    s.step = m_step;
    s.time = m_time;
    s.lastMaxSpeed = m_stats.maxSpeed;
    s.particles = m_p;
    s.neighborX = m_xs;
    s.neighborY = m_ys;
    if (!m_moving.empty())
        s.wallRestX = m_restX;
    return s;
}

void MpsSolver::importState(const MpsState& s) {
    const std::size_t n = m_p.size();
    const auto bad = [](const std::string& what) {
        throw std::invalid_argument("MpsSolver::importState: " + what);
    };
    const Particles& q = s.particles;
    if (q.size() != n || !q.consistent()) {
        bad(fmt::format("state of {} particles, solver has {}", q.size(), n));
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (q.kind[i] != m_p.kind[i]) {
            bad(fmt::format("particle {} is {} in the state, {} in the solver", i,
                            toString(q.kind[i]), toString(m_p.kind[i])));
        }
        if (!m_domain.contains(q.x[i], q.y[i])) {
            bad(fmt::format("particle {} at ({}, {}) is outside the domain", i, q.x[i], q.y[i]));
        }
    }
    if (s.neighborX.size() != n || s.neighborY.size() != n)
        bad("neighbour-build positions of another size");
    if (s.wallRestX.empty() != m_moving.empty() ||
        (!s.wallRestX.empty() && s.wallRestX.size() != n)) {
        bad(m_moving.empty() ? "state has a moving wall, the solver none (set it first)"
                             : "solver has a moving wall, the state none");
    }
    if (!(s.step >= 0) || !std::isfinite(s.time) || !std::isfinite(s.lastMaxSpeed))
        bad("bad step, time or speed");

    bool finite = true;
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(s.neighborX[i]) || !std::isfinite(s.neighborY[i])) {
            finite = false;
        } else if (!m_domain.contains(s.neighborX[i], s.neighborY[i])) {
            bad(fmt::format("neighbour-build position of particle {} is outside the domain", i));
        }
    }
    m_p = q;
    m_step = s.step;
    m_time = s.time;
    if (!s.wallRestX.empty())
        m_restX = s.wallRestX;
    if (finite) {
        rebuildNeighbors(s.neighborX,
                         s.neighborY); // the same lists, in the same order, as at export
    } else {
        // A particle moved after the last build (NaN): the next step rebuilds from the positions.
        m_xs = s.neighborX;
        m_ys = s.neighborY;
    }
    m_stats = StepStats{};
    m_stats.step = m_step;
    m_stats.time = m_time;
    m_stats.maxSpeed = s.lastMaxSpeed;
}

} // namespace swell::bake
