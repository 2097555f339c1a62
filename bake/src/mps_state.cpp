// MpsSolver::exportState / importState (checkpoint / resume, docs/scenes.md "Checkpoints") and
// removeWater. Kept apart from the numerics in mps_solver.cpp: plain copies and edits of the state
// that survives from step to step.
#include <algorithm>
#include <cmath>
#include <cstddef>
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
    s.removedWater = m_removed;
    return s;
}

namespace {
/// Keeps the entries of `v` whose `drop` flag is 0, in order.
template <class T> void compact(std::vector<T>& v, const std::vector<std::uint8_t>& drop) {
    std::size_t k = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!drop[i])
            v[k++] = v[i];
    }
    v.resize(k);
}
} // namespace

void MpsSolver::removeWater(std::span<const std::size_t> indices) {
    const std::size_t n = m_p.size();
    const auto bad = [](const std::string& what) {
        throw std::invalid_argument("MpsSolver::removeWater: " + what);
    };
    std::vector<std::uint8_t> drop(n, 0);
    for (std::size_t i : indices) {
        if (i >= n || m_p.kind[i] != ParticleKind::Water)
            bad(fmt::format("particle {} is not water", i));
        if (drop[i])
            bad(fmt::format("particle {} is named twice", i));
        drop[i] = 1;
    }
    if (indices.empty())
        return;
    if (indices.size() >= m_p.count(ParticleKind::Water))
        bad("no water would remain");
    // The current particles are the initial ones but for those removed before, in order.
    std::vector<std::uint32_t> gone;
    for (std::size_t i = 0, initial = 0, r = 0; i < n; ++i, ++initial) {
        for (; r < m_removed.size() && m_removed[r] == initial; ++r)
            ++initial;
        if (drop[i])
            gone.push_back(static_cast<std::uint32_t>(initial));
    }
    const auto middle = static_cast<std::ptrdiff_t>(m_removed.size());
    m_removed.insert(m_removed.end(), gone.begin(), gone.end());
    std::inplace_merge(m_removed.begin(), m_removed.begin() + middle, m_removed.end());
    std::vector<std::uint32_t> newIndex(n, 0);
    for (std::size_t i = 0, k = 0; i < n; ++i) {
        if (!drop[i])
            newIndex[i] = static_cast<std::uint32_t>(k++);
    }
    for (std::uint32_t& i : m_wall.particles) // fixed particles: never removed
        i = newIndex[i];

    // The state that lasts from step to step, and the last step's flags (classification).
    for (auto* v : {&m_p.x, &m_p.y, &m_p.vx, &m_p.vy, &m_p.p, &m_p.n, &m_xs, &m_ys})
        compact(*v, drop);
    compact(m_p.kind, drop);
    compact(m_surface, drop);
    compact(m_layer, drop);
    if (!m_moving.empty()) {
        compact(m_moving, drop);
        compact(m_restX, drop);
    }
    // Work arrays of one step: only their length follows.
    const std::size_t k = m_p.size();
    for (auto* v : {&m_xStar, &m_yStar, &m_uStar, &m_vStar, &m_uC, &m_vC, &m_divU, &m_fx, &m_fy,
                    &m_fNorm, &m_shiftX, &m_shiftY, &m_nPack}) {
        v->resize(k);
    }
    m_row.resize(k);

    // The neighbour lists name particles by index: build them again from the positions of the
    // last build (the Verlet reference stays). Where a particle was moved since (its NaN
    // reference, relocateWater), the next step rebuilds from the current positions anyway.
    if (std::all_of(m_xs.begin(), m_xs.end(), [](double v) { return std::isfinite(v); }) &&
        std::all_of(m_ys.begin(), m_ys.end(), [](double v) { return std::isfinite(v); })) {
        const std::vector<double> x = m_xs, y = m_ys; // rebuildNeighbors copies into m_xs
        rebuildNeighbors(x, y);
    }
}

void MpsSolver::importState(const MpsState& s) {
    const std::size_t before = m_p.size();
    const auto bad = [](const std::string& what) {
        throw std::invalid_argument("MpsSolver::importState: " + what);
    };
    const Particles& q = s.particles;
    // Water the exporting solver removed goes here too (this solver must have removed none).
    if (s.removedWater != m_removed) {
        if (!m_removed.empty())
            bad("the state and the solver have removed different water");
        if (q.size() + s.removedWater.size() != before || !q.consistent()) {
            bad(fmt::format("state of {} particles and {} removed, solver has {}", q.size(),
                            s.removedWater.size(), before));
        }
        std::vector<std::size_t> gone(s.removedWater.begin(), s.removedWater.end());
        removeWater(gone);
    }
    const std::size_t n = m_p.size();
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
