#include "swell/bake/mps_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "swell/bake/error.h"

namespace swell::bake {
namespace {

constexpr double kDim = 2.0; // d in K&O's Laplacian and gradient models

// Loops shorter than this run on one thread: below it an OpenMP fork/join costs more than
// it saves, and on a busy machine a woken thread may wait a whole scheduler slice.
constexpr std::size_t kParallelMin = 4096;
// Same for the cheap per-element vector operations of the conjugate gradient.
constexpr std::size_t kParallelVector = 65536;

using Clock = std::chrono::steady_clock;

/// Adds the wall time since construction (or the last lap) to one phase slot.
class PhaseTimer {
public:
    explicit PhaseTimer(StepStats& stats) : m_stats(stats), m_start(Clock::now()) {}
    void lap(Phase phase) {
        const auto now = Clock::now();
        m_stats.phaseSeconds[static_cast<std::size_t>(phase)] +=
            std::chrono::duration<double>(now - m_start).count();
        m_start = now;
    }

private:
    StepStats& m_stats;
    Clock::time_point m_start;
};

bool isFixed(ParticleKind k) { return k != ParticleKind::Water; }

double dot(const double* a, const double* b, std::size_t n) {
    double s = 0.0;
#pragma omp parallel for reduction(+ : s) schedule(static) if(n >= kParallelVector)
    for (std::size_t i = 0; i < n; ++i) s += a[i] * b[i];
    return s;
}

} // namespace

std::string_view toString(Phase phase) {
    switch (phase) {
    case Phase::Neighbors: return "neighbors";
    case Phase::Explicit: return "explicit";
    case Phase::Density: return "density";
    case Phase::PpeAssembly: return "ppe_assembly";
    case Phase::PpeSolve: return "ppe_solve";
    case Phase::Correction: return "correction";
    }
    return "?";
}

std::string_view toString(Preconditioner p) {
    switch (p) {
    case Preconditioner::Jacobi: return "jacobi";
    case Preconditioner::SymmetricGaussSeidel: return "symmetric_gauss_seidel";
    case Preconditioner::IncompleteCholesky: return "incomplete_cholesky";
    case Preconditioner::TwoLevel: return "two_level";
    }
    return "?";
}

std::string_view toString(SourceTerm s) { return s == SourceTerm::Relaxed ? "relaxed" : "mixed"; }

MpsSolver::MpsSolver(const PhysicsParams& physics, const SolverParams& solver, Particles particles,
                     double spacing, const Box& domain)
    : m_phys(physics), m_par(solver), m_p(std::move(particles)), m_l0(spacing), m_domain(domain) {
    const auto require = [](bool ok, const char* what) {
        if (!ok) throw std::invalid_argument(std::string("MpsSolver: ") + what);
    };
    require(m_l0 > 0.0 && std::isfinite(m_l0), "spacing must be positive");
    require(m_phys.density > 0.0, "density must be positive");
    require(m_phys.kinematicViscosity >= 0.0, "viscosity must not be negative");
    require(m_par.dt > 0.0, "dt must be positive");
    require(m_par.reDensity > 1.0 && m_par.reLaplacian > 1.0, "kernel radii must exceed one spacing");
    require(m_par.ppeTolerance > 0.0 && m_par.ppeMaxIterations > 0, "PPE tolerance and iterations must be positive");
    require(m_par.neighborSkin >= 0.0 && m_par.maxNeighbors > 0, "bad neighbour skin or capacity");
    require(m_par.courantLimit > 0.0 && m_par.courantTarget > 0.0, "Courant numbers must be positive");
    const std::size_t n = m_p.size();
    require(n > 0 && m_p.count(ParticleKind::Water) > 0, "no water particles");
    require(m_p.consistent(), "particle arrays differ in length");
    for (std::size_t i = 0; i < n; ++i) {
        if (!m_domain.contains(m_p.x[i], m_p.y[i])) {
            throw std::invalid_argument(fmt::format("MpsSolver: particle {} at ({}, {}) is outside the domain", i,
                                                    m_p.x[i], m_p.y[i]));
        }
    }

    m_reN = m_par.reDensity * m_l0;
    m_reL = m_par.reLaplacian * m_l0;
    m_collide = m_par.collisionDistance * m_l0;
    m_reList = std::max({m_reN, m_reL, m_collide}) + m_par.neighborSkin * m_l0;
    // The number-density kernel (density, gradient, p_min) and the collisions reach only
    // re_N: they scan a short sub-list, half as long as the full one at the textbook radii.
    m_reShort = std::min(m_reList, std::max(m_reN, m_collide) + m_par.neighborSkin * m_l0);
    m_latN = latticeConstants(m_l0, m_reN);
    m_latL = latticeConstants(m_l0, m_reL);
    m_grid.configure(m_domain, m_reList, n, m_par.maxNeighbors);

    m_xs.assign(n, 0.0);
    m_ys.assign(n, 0.0);
    m_xStar.assign(n, 0.0);
    m_yStar.assign(n, 0.0);
    m_uStar.assign(n, 0.0);
    m_vStar.assign(n, 0.0);
    m_uC.assign(n, 0.0);
    m_vC.assign(n, 0.0);
    m_divU.assign(n, 0.0);
    m_surface.assign(n, 0);
    m_row.assign(n, -1);
    m_rowParticle.assign(n, 0);
    const std::size_t cap = n * (static_cast<std::size_t>(m_par.maxNeighbors) + 1);
    m_rowPtr.assign(n + 1, 0);
    m_rowNnz.assign(n, 0);
    m_col.assign(cap, 0);
    m_val.assign(cap, 0.0);
    m_ic.assign(cap, 0.0);
    m_diagPos.assign(n, 0);
    m_icMark.assign(n, -1);
    m_aggMap.assign(static_cast<std::size_t>(m_grid.cellsX()) * static_cast<std::size_t>(m_grid.cellsY()), -1);
    m_aggOf.assign(n, 0);
    m_rc.assign(n, 0.0);
    m_zc.assign(n, 0.0);
    m_band.assign(std::min<std::size_t>(n * 64, std::size_t{1} << 22), 0.0);
    for (auto* v : {&m_b, &m_x, &m_r, &m_z, &m_d, &m_q, &m_invDiag}) v->assign(n, 0.0);
    // Initial number density, so n is meaningful before the first step.
    rebuildNeighbors(m_p.x, m_p.y);
    for (std::size_t i = 0; i < n; ++i) {
        double s = 0.0;
        for (std::uint32_t j : m_grid.neighbors(i)) {
            s += mpsWeight(std::hypot(m_p.x[j] - m_p.x[i], m_p.y[j] - m_p.y[i]), m_reN);
        }
        m_p.n[i] = s;
    }
}

void MpsSolver::setMovingWall(MovingWall wall) {
    const std::size_t n = m_p.size();
    if (!wall.motion) throw std::invalid_argument("MpsSolver::setMovingWall: no motion function");
    m_moving.assign(n, 0);
    m_restX.assign(n, 0.0);
    const double X = wall.motion(m_time).displacement;
    for (std::uint32_t i : wall.particles) {
        if (i >= n || !isFixed(m_p.kind[i])) {
            throw std::invalid_argument(fmt::format("MpsSolver::setMovingWall: particle {} is not a wall particle", i));
        }
        m_moving[i] = 1;
        m_restX[i] = m_p.x[i] - X;
    }
    m_wall = std::move(wall);
}

void MpsSolver::setInflow(const Box& zone, double velocity) {
    if (!std::isfinite(velocity)) throw std::invalid_argument("MpsSolver::setInflow: velocity must be finite");
    m_hasInflow = true;
    m_inflowZone = zone;
    m_inflowVelocity = velocity;
}

void MpsSolver::relocateWater(std::size_t i, double x, double y, double vx, double vy) {
    if (i >= m_p.size() || m_p.kind[i] != ParticleKind::Water) {
        throw std::invalid_argument(fmt::format("MpsSolver::relocateWater: particle {} is not water", i));
    }
    if (!m_domain.contains(x, y)) {
        throw std::invalid_argument(fmt::format("MpsSolver::relocateWater: ({}, {}) is outside the domain", x, y));
    }
    m_p.x[i] = x;
    m_p.y[i] = y;
    m_p.vx[i] = vx;
    m_p.vy[i] = vy;
    m_xs[i] = std::numeric_limits<double>::quiet_NaN(); // forces a neighbour rebuild next step
}

std::vector<std::uint32_t> MpsSolver::ppeRowParticles() const {
    return {m_rowParticle.begin(), m_rowParticle.begin() + static_cast<std::ptrdiff_t>(m_rows)};
}

Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>> MpsSolver::ppeMatrix() const {
    const auto rows = static_cast<Eigen::Index>(m_rows);
    int nnz = 0;
    for (std::size_t r = 0; r < m_rows; ++r) nnz += m_rowNnz[r];
    return {rows, rows, nnz, m_rowPtr.data(), m_col.data(), m_val.data(), m_rowNnz.data()};
}

Eigen::Map<const Eigen::VectorXd> MpsSolver::ppeRhs() const {
    return {m_b.data(), static_cast<Eigen::Index>(m_rows)};
}

Eigen::Map<const Eigen::VectorXd> MpsSolver::ppeSolution() const {
    return {m_x.data(), static_cast<Eigen::Index>(m_rows)};
}

void MpsSolver::fail(std::size_t particle, const std::string& reason) const {
    throw DivergenceError(m_step + 1, m_time + m_stats.dt, particle, reason);
}

void MpsSolver::rebuildNeighbors(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = m_p.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
            fail(i, fmt::format("non-finite position of {} particle: ({}, {}) m, velocity ({}, {}) m/s",
                                toString(m_p.kind[i]), x[i], y[i], m_p.vx[i], m_p.vy[i]));
        }
        if (!m_domain.contains(x[i], y[i])) {
            fail(i, fmt::format("{} particle at ({:.6g}, {:.6g}) m left the domain [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] m",
                                toString(m_p.kind[i]), x[i], y[i], m_domain.x0, m_domain.x1, m_domain.y0,
                                m_domain.y1));
        }
    }
    if (!m_grid.build(x, y, m_reList, m_reShort)) {
        fail(m_grid.overflowParticle(),
             fmt::format("more than {} neighbours within {:.3g} l0 (particles clumping; raise solver.max_neighbors "
                         "only if this is expected)", m_par.maxNeighbors, m_reList / m_l0));
    }
    std::copy(x.begin(), x.end(), m_xs.begin());
    std::copy(y.begin(), y.end(), m_ys.begin());
    ++m_stats.neighborRebuilds;
}

bool MpsSolver::skinUsedUp(const std::vector<double>& x, const std::vector<double>& y) const {
    // Verlet criterion: lists built with radius re + skin stay complete while no particle
    // has moved more than skin / 2 since the build.
    const double half = 0.5 * m_par.neighborSkin * m_l0;
    const double limit2 = half * half;
    const std::size_t n = m_p.size();
    int used = 0;
#pragma omp parallel for reduction(| : used) schedule(static) if(n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        const double dx = x[i] - m_xs[i];
        const double dy = y[i] - m_ys[i];
        // A NaN displacement also counts: the rebuild then reports the particle.
        if (!(dx * dx + dy * dy <= limit2)) used = 1;
    }
    return used != 0;
}

double MpsSolver::chooseDt() const {
    if (!m_par.adaptiveDt || m_stats.maxSpeed <= 0.0) return m_par.dt;
    return std::min(m_par.dt, m_par.courantTarget * m_l0 / m_stats.maxSpeed);
}

const StepStats& MpsSolver::step() {
    const double dt = chooseDt();
    const double lastMaxSpeed = m_stats.maxSpeed;
    m_stats = StepStats{};
    m_stats.step = m_step + 1;
    m_stats.dt = dt;
    m_stats.maxSpeed = lastMaxSpeed;
    PhaseTimer timer(m_stats);

    if (skinUsedUp(m_p.x, m_p.y)) rebuildNeighbors(m_p.x, m_p.y);
    timer.lap(Phase::Neighbors);
    explicitPhase(dt);
    timer.lap(Phase::Explicit);
    if (skinUsedUp(m_xStar, m_yStar)) rebuildNeighbors(m_xStar, m_yStar);
    timer.lap(Phase::Neighbors);
    densityPhase(dt);
    timer.lap(Phase::Density);
    assemblePpe(dt);
    timer.lap(Phase::PpeAssembly);
    solvePpe();
    timer.lap(Phase::PpeSolve);
    correctionPhase(dt);
    checkState(dt);
    timer.lap(Phase::Correction);

    m_time += dt;
    ++m_step;
    m_stats.time = m_time;
    return m_stats;
}

void MpsSolver::explicitPhase(double dt) {
    const std::size_t n = m_p.size();
    const double coefL = 2.0 * kDim / (m_latL.n0 * m_latL.lambda); // K&O 1996 Laplacian model prefactor
    const double nu = m_phys.kinematicViscosity;
    const double g = m_phys.gravity;
    const double reL2 = m_reL * m_reL;
    // Algorithm 1, step 3: move the pushing wall to its prescribed place at the end of the step.
    const PistonState wall = m_wall.motion ? m_wall.motion(m_time + dt) : PistonState{};
    const bool anyMoving = !m_moving.empty();
#pragma omp parallel for schedule(static) if(n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        if (isFixed(m_p.kind[i])) {
            const bool moving = anyMoving && m_moving[i];
            m_xStar[i] = moving ? m_restX[i] + wall.displacement : m_p.x[i];
            m_yStar[i] = m_p.y[i];
            m_uStar[i] = moving ? wall.velocity : 0.0;
            m_vStar[i] = 0.0;
            continue;
        }
        // K&O 1996 Laplacian model: nu 2d/(lambda n0) sum (u_j - u_i) w(r_ij), re = 3.1 l0.
        double lx = 0.0, ly = 0.0;
        for (std::uint32_t j : m_grid.neighbors(i)) {
            const double dx = m_p.x[j] - m_p.x[i];
            const double dy = m_p.y[j] - m_p.y[i];
            const double r2 = dx * dx + dy * dy;
            if (r2 >= reL2) continue;
            const double w = mpsWeight(std::sqrt(r2), m_reL);
            lx += (m_p.vx[j] - m_p.vx[i]) * w;
            ly += (m_p.vy[j] - m_p.vy[i]) * w;
        }
        // Explicit part of paper eq. (2): u* = u + dt (nu lap u + f), r* = r + dt u*.
        m_uStar[i] = m_p.vx[i] + dt * (nu * coefL * lx);
        if (m_hasInflow && m_inflowZone.contains(m_p.x[i], m_p.y[i])) m_uStar[i] = m_inflowVelocity; // Sec. 3.3.2 inflow
        m_vStar[i] = m_p.vy[i] + dt * (nu * coefL * ly - g);
        m_xStar[i] = m_p.x[i] + dt * m_uStar[i];
        m_yStar[i] = m_p.y[i] + dt * m_vStar[i];
    }

    // Collision model of the textbook code: a water particle approaching another closer than
    // collisionDistance loses the approaching part of its relative velocity, with restitution
    // e, as in an equal-mass impact. Gather form: each i only changes itself.
    const double c2 = m_collide * m_collide;
    const double e = m_par.restitution;
    std::size_t collisions = 0;
#pragma omp parallel for schedule(static) reduction(+ : collisions) if(n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        m_uC[i] = m_uStar[i];
        m_vC[i] = m_vStar[i];
        if (isFixed(m_p.kind[i])) continue;
        for (std::uint32_t j : m_grid.shortNeighbors(i)) {
            const double dx = m_xStar[j] - m_xStar[i];
            const double dy = m_yStar[j] - m_yStar[i];
            const double r2 = dx * dx + dy * dy;
            if (r2 >= c2 || r2 <= 0.0) continue;
            const double r = std::sqrt(r2);
            const double nx = dx / r, ny = dy / r;
            const double approach = (m_uC[i] - m_uStar[j]) * nx + (m_vC[i] - m_vStar[j]) * ny;
            if (approach > 0.0) {
                const double impulse = 0.5 * (1.0 + e) * approach; // m_j / (m_i + m_j) = 1/2
                m_uC[i] -= impulse * nx;
                m_vC[i] -= impulse * ny;
                ++collisions;
            }
        }
    }
    m_stats.collisions = collisions;
#pragma omp parallel for schedule(static) if(n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        if (isFixed(m_p.kind[i])) continue;
        m_xStar[i] += (m_uC[i] - m_uStar[i]) * dt;
        m_yStar[i] += (m_vC[i] - m_vStar[i]) * dt;
        m_uStar[i] = m_uC[i];
        m_vStar[i] = m_vC[i];
    }
}

void MpsSolver::densityPhase(double /*dt*/) {
    const std::size_t n = m_p.size();
    const double reN2 = m_reN * m_reN;
    const double threshold = m_par.surfaceThreshold * m_latN.n0;
    const bool mixed = m_par.sourceTerm == SourceTerm::Mixed;
    const double coefD = kDim / m_latN.n0;
    std::size_t surface = 0;
#pragma omp parallel for schedule(static) reduction(+ : surface) if(n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        double s = 0.0;
        double div = 0.0;
        for (std::uint32_t j : m_grid.shortNeighbors(i)) {
            const double dx = m_xStar[j] - m_xStar[i];
            const double dy = m_yStar[j] - m_yStar[i];
            const double r2 = dx * dx + dy * dy;
            if (r2 >= reN2) continue;
            const double w = mpsWeight(std::sqrt(r2), m_reN);
            s += w; // K&O 1996 particle number density, at r*
            if (mixed && m_p.kind[j] != ParticleKind::Dummy) {
                // Divergence model: d/n0 sum (u_j - u_i).(r_j - r_i) / r^2 w
                div += ((m_uStar[j] - m_uStar[i]) * dx + (m_vStar[j] - m_vStar[i]) * dy) / r2 * w;
            }
        }
        m_p.n[i] = s;
        m_divU[i] = coefD * div;
        if (m_p.kind[i] == ParticleKind::Dummy) {
            m_surface[i] = 2; // not in the pressure solve
        } else {
            // Paper eq. (3), the K&O 1996 free-surface condition: free surface where n* < beta n0, p = 0 there.
            m_surface[i] = s < threshold ? 1 : 0;
            surface += m_surface[i];
        }
    }
    m_stats.surfaceParticles = surface;
}

void MpsSolver::assemblePpe(double dt) {
    // Rows: water and wall particles that are not on the free surface, in grid order so the
    // matrix has good locality and each row's columns come out sorted.
    const std::span<const std::uint32_t> order = m_grid.sorted();
    int rows = 0;
    for (std::uint32_t i : order) {
        if (m_surface[i] == 0) {
            m_row[i] = rows;
            m_rowParticle[static_cast<std::size_t>(rows)] = i;
            ++rows;
        } else {
            m_row[i] = -1;
        }
    }
    m_rows = static_cast<std::size_t>(rows);
    const double reL2 = m_reL * m_reL;
    // Each row gets room for its whole neighbour list plus the diagonal, so one pass fills it;
    // m_rowNnz says how much of it is used (sparse rows with small gaps, Eigen's uncompressed layout).
    m_rowPtr[0] = 0;
    for (int r = 0; r < rows; ++r) {
        const std::uint32_t i = m_rowParticle[static_cast<std::size_t>(r)];
        m_rowPtr[static_cast<std::size_t>(r) + 1] =
            m_rowPtr[static_cast<std::size_t>(r)] + static_cast<int>(m_grid.neighbors(i).size()) + 1;
    }

    // K&O 1996 pressure Poisson equation with the Laplacian model:
    //   sum_j a w_ij (p_i - p_j) / rho + C p_i / dt^2 = RHS,  a = 2d / (lambda n0),
    // where surface neighbours (p_j = 0) only add to the diagonal, dummies are left out, and
    // the artificial compressibility C (textbook code) makes the system strictly diagonally
    // dominant, hence symmetric positive definite.
    const double a = 2.0 * kDim / (m_latL.n0 * m_latL.lambda) / m_phys.density;
    const double compress = m_par.compressibility / (dt * dt);
    const double gamma = m_par.relaxation;
    const double n0 = m_latN.n0;
    const bool mixed = m_par.sourceTerm == SourceTerm::Mixed;
#pragma omp parallel for schedule(static) if(static_cast<std::size_t>(rows) >= kParallelMin)
    for (int r = 0; r < rows; ++r) {
        const std::uint32_t i = m_rowParticle[static_cast<std::size_t>(r)];
        const int begin = m_rowPtr[static_cast<std::size_t>(r)];
        int pos = begin;
        int diag = -1;
        double diagValue = compress;
        for (std::uint32_t j : m_grid.neighbors(i)) {
            if (m_surface[j] == 2) continue;
            const double dx = m_xStar[j] - m_xStar[i];
            const double dy = m_yStar[j] - m_yStar[i];
            const double r2 = dx * dx + dy * dy;
            if (r2 >= reL2) continue;
            const double c = a * mpsWeight(std::sqrt(r2), m_reL);
            diagValue += c;
            const int cj = m_row[j];
            if (cj < 0) continue;
            if (diag < 0 && cj > r) { // columns are sorted: the diagonal goes here
                diag = pos++;
            }
            m_col[static_cast<std::size_t>(pos)] = cj;
            m_val[static_cast<std::size_t>(pos)] = -c;
            ++pos;
        }
        if (diag < 0) diag = pos++;
        m_rowNnz[static_cast<std::size_t>(r)] = pos - begin;
        m_col[static_cast<std::size_t>(diag)] = r;
        m_val[static_cast<std::size_t>(diag)] = diagValue;
        m_diagPos[static_cast<std::size_t>(r)] = diag;
        m_invDiag[static_cast<std::size_t>(r)] = 1.0 / diagValue;
        // K&O 1996 PPE source, relaxed (textbook): gamma / dt^2 (n* - n0) / n0. Mixed
        // (Tanaka & Masunaga 2010): - div(u*) / dt + gamma / dt^2 (n* - n0) / n0.
        double rhs = gamma / (dt * dt) * (m_p.n[i] - n0) / n0;
        if (mixed) rhs -= m_divU[i] / dt;
        m_b[static_cast<std::size_t>(r)] = rhs;
        m_x[static_cast<std::size_t>(r)] = m_p.p[i]; // warm start from the last pressure
    }
}

double MpsSolver::matVec(const double* v, double* out) const {
    const int rows = static_cast<int>(m_rows);
    double vAv = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : vAv) if(static_cast<std::size_t>(rows) >= kParallelMin)
    for (int r = 0; r < rows; ++r) {
        const int end = rowEnd(r);
        double s = 0.0;
        for (int k = m_rowPtr[static_cast<std::size_t>(r)]; k < end; ++k) {
            s += m_val[static_cast<std::size_t>(k)] * v[m_col[static_cast<std::size_t>(k)]];
        }
        out[r] = s;
        vAv += v[r] * s;
    }
    return vAv;
}

void MpsSolver::factorIncompleteCholesky() {
    // IC(0): L L^T ~ A with L on A's lower pattern. Row-by-row (up-looking):
    //   L_ij = (A_ij - sum_{k<j} L_ik L_jk) / L_jj,  L_ii = sqrt(A_ii - sum_{k<i} L_ik^2).
    // A is a diagonally dominant M-matrix, so no pivot can vanish.
    const int rows = static_cast<int>(m_rows);
    for (int i = 0; i < rows; ++i) {
        const int begin = m_rowPtr[static_cast<std::size_t>(i)];
        const int dpos = m_diagPos[static_cast<std::size_t>(i)];
        for (int k = begin; k < dpos; ++k) m_icMark[static_cast<std::size_t>(m_col[static_cast<std::size_t>(k)])] = k;
        double diagSum = 0.0;
        for (int k = begin; k < dpos; ++k) {
            const int j = m_col[static_cast<std::size_t>(k)];
            double s = m_val[static_cast<std::size_t>(k)];
            const int jb = m_rowPtr[static_cast<std::size_t>(j)];
            const int jd = m_diagPos[static_cast<std::size_t>(j)];
            for (int q = jb; q < jd; ++q) { // sum over k < j present in both rows
                const int pos = m_icMark[static_cast<std::size_t>(m_col[static_cast<std::size_t>(q)])];
                if (pos >= 0) s -= m_ic[static_cast<std::size_t>(pos)] * m_ic[static_cast<std::size_t>(q)];
            }
            const double lij = s / m_ic[static_cast<std::size_t>(jd)];
            m_ic[static_cast<std::size_t>(k)] = lij;
            diagSum += lij * lij;
        }
        const double pivot = m_val[static_cast<std::size_t>(dpos)] - diagSum;
        // Safeguard (never expected for an M-matrix): fall back to the diagonal.
        m_ic[static_cast<std::size_t>(dpos)] = pivot > 0.0 ? std::sqrt(pivot) : std::sqrt(m_val[static_cast<std::size_t>(dpos)]);
        for (int k = begin; k < dpos; ++k) m_icMark[static_cast<std::size_t>(m_col[static_cast<std::size_t>(k)])] = -1;
    }
}

void MpsSolver::setupTwoLevel() {
    // Aggregates: one per grid cell holding unknowns, numbered along the shorter side of the
    // occupied cells first, so the coarse matrix (cells couple only to adjacent cells) has a
    // band about as wide as the shorter side.
    const int rows = static_cast<int>(m_rows);
    const int nx = m_grid.cellsX();
    int x0 = nx, x1 = -1, y0 = m_grid.cellsY(), y1 = -1;
    for (int r = 0; r < rows; ++r) {
        const std::uint32_t cell = m_grid.cellIndex(m_rowParticle[static_cast<std::size_t>(r)]);
        m_aggMap[cell] = -2; // used
        const int cx = static_cast<int>(cell) % nx, cy = static_cast<int>(cell) / nx;
        x0 = std::min(x0, cx);
        x1 = std::max(x1, cx);
        y0 = std::min(y0, cy);
        y1 = std::max(y1, cy);
    }
    int nAgg = 0;
    if (x1 - x0 >= y1 - y0) { // wide: number column by column
        for (int cx = x0; cx <= x1; ++cx) {
            for (int cy = y0; cy <= y1; ++cy) {
                int& id = m_aggMap[static_cast<std::size_t>(cy * nx + cx)];
                if (id == -2) id = nAgg++;
            }
        }
    } else { // tall: row by row
        for (int cy = y0; cy <= y1; ++cy) {
            for (int cx = x0; cx <= x1; ++cx) {
                int& id = m_aggMap[static_cast<std::size_t>(cy * nx + cx)];
                if (id == -2) id = nAgg++;
            }
        }
    }
    for (int r = 0; r < rows; ++r) {
        m_aggOf[static_cast<std::size_t>(r)] = m_aggMap[m_grid.cellIndex(m_rowParticle[static_cast<std::size_t>(r)])];
    }
    for (int r = 0; r < rows; ++r) m_aggMap[m_grid.cellIndex(m_rowParticle[static_cast<std::size_t>(r)])] = -1;
    m_nAgg = nAgg;
    int bw = 0;
    for (int r = 0; r < rows; ++r) {
        const int I = m_aggOf[static_cast<std::size_t>(r)];
        for (int k = m_rowPtr[static_cast<std::size_t>(r)]; k < rowEnd(r); ++k) {
            bw = std::max(bw, I - m_aggOf[static_cast<std::size_t>(m_col[static_cast<std::size_t>(k)])]);
        }
    }
    m_bandwidth = bw;
    const std::size_t width = static_cast<std::size_t>(bw) + 1;
    const std::size_t need = static_cast<std::size_t>(nAgg) * width;
    if (m_band.size() < need) m_band.resize(need); // grows only for an unusually wide band
    double* band = m_band.data();
    // Coarse matrix A_c = P^T A P (P: piecewise constant on aggregates), lower band only:
    // band[I * width + (I - J)] = sum of A_ij over i in I, j in J.
    std::fill(band, band + need, 0.0);
    for (int r = 0; r < rows; ++r) {
        const int I = m_aggOf[static_cast<std::size_t>(r)];
        double* rowI = band + static_cast<std::size_t>(I) * width;
        for (int k = m_rowPtr[static_cast<std::size_t>(r)]; k < rowEnd(r); ++k) {
            const int J = m_aggOf[static_cast<std::size_t>(m_col[static_cast<std::size_t>(k)])];
            if (J <= I) rowI[I - J] += m_val[static_cast<std::size_t>(k)];
        }
    }
    // Band Cholesky in place: L(i, j) at band[i * width + (i - j)].
    for (int i = 0; i < nAgg; ++i) {
        double* Li = band + static_cast<std::size_t>(i) * width;
        for (int j = std::max(0, i - bw); j <= i; ++j) {
            const double* Lj = band + static_cast<std::size_t>(j) * width;
            double s = Li[i - j];
            for (int k = std::max(0, i - bw); k < j; ++k) s -= Li[i - k] * Lj[j - k];
            if (j == i) {
                Li[0] = std::sqrt(std::max(s, 1e-300)); // SPD: s > 0 up to round-off
            } else {
                Li[i - j] = s / Lj[0];
            }
        }
    }
}

void MpsSolver::applyPreconditioner(const double* r, double* z) const {
    const int rows = static_cast<int>(m_rows);
    if (m_par.preconditioner == Preconditioner::TwoLevel) {
        // z = D^-1 r + P A_c^-1 P^T r (additive two-level, symmetric positive definite).
        const int nAgg = m_nAgg;
        const int bw = m_bandwidth;
        const std::size_t width = static_cast<std::size_t>(bw) + 1;
        const double* band = m_band.data();
        double* rc = const_cast<double*>(m_rc.data()); // scratch (logically const)
        double* zc = const_cast<double*>(m_zc.data());
        std::fill(rc, rc + nAgg, 0.0);
        for (int q = 0; q < rows; ++q) rc[m_aggOf[static_cast<std::size_t>(q)]] += r[q];
        for (int i = 0; i < nAgg; ++i) { // L y = rc
            const double* Li = band + static_cast<std::size_t>(i) * width;
            double s = rc[i];
            for (int k = std::max(0, i - bw); k < i; ++k) s -= Li[i - k] * zc[k];
            zc[i] = s / Li[0];
        }
        for (int i = nAgg - 1; i >= 0; --i) { // L^T zc = y
            double s = zc[i];
            for (int k = i + 1; k <= std::min(nAgg - 1, i + bw); ++k) {
                s -= band[static_cast<std::size_t>(k) * width + static_cast<std::size_t>(k - i)] * zc[k];
            }
            zc[i] = s / band[static_cast<std::size_t>(i) * width];
        }
#pragma omp parallel for schedule(static) if(static_cast<std::size_t>(rows) >= kParallelVector)
        for (int q = 0; q < rows; ++q) {
            z[q] = r[q] * m_invDiag[static_cast<std::size_t>(q)] + zc[m_aggOf[static_cast<std::size_t>(q)]];
        }
        return;
    }
    if (m_par.preconditioner == Preconditioner::Jacobi) {
#pragma omp parallel for schedule(static) if(static_cast<std::size_t>(rows) >= kParallelMin)
        for (int i = 0; i < rows; ++i) z[i] = r[i] * m_invDiag[static_cast<std::size_t>(i)];
        return;
    }
    if (m_par.preconditioner == Preconditioner::SymmetricGaussSeidel) {
        // M = (D + L) D^-1 (D + U), U = L^T: forward sweep (D + L) y = r, then backward
        // sweep (D + U) z = D y, i.e. z_i = y_i - (sum_{j>i} a_ij z_j) / a_ii.
        for (int i = 0; i < rows; ++i) {
            double s = r[i];
            const int dpos = m_diagPos[static_cast<std::size_t>(i)];
            for (int k = m_rowPtr[static_cast<std::size_t>(i)]; k < dpos; ++k) {
                s -= m_val[static_cast<std::size_t>(k)] * z[m_col[static_cast<std::size_t>(k)]];
            }
            z[i] = s * m_invDiag[static_cast<std::size_t>(i)];
        }
        for (int i = rows - 1; i >= 0; --i) {
            double s = 0.0;
            const int dpos = m_diagPos[static_cast<std::size_t>(i)];
            for (int k = dpos + 1; k < rowEnd(i); ++k) {
                s += m_val[static_cast<std::size_t>(k)] * z[m_col[static_cast<std::size_t>(k)]];
            }
            z[i] -= s * m_invDiag[static_cast<std::size_t>(i)];
        }
        return;
    }
    // Forward solve L y = r (y stored in z), then backward L^T z = y.
    for (int i = 0; i < rows; ++i) {
        double s = r[i];
        const int dpos = m_diagPos[static_cast<std::size_t>(i)];
        for (int k = m_rowPtr[static_cast<std::size_t>(i)]; k < dpos; ++k) {
            s -= m_ic[static_cast<std::size_t>(k)] * z[m_col[static_cast<std::size_t>(k)]];
        }
        z[i] = s / m_ic[static_cast<std::size_t>(dpos)];
    }
    for (int i = rows - 1; i >= 0; --i) {
        const int dpos = m_diagPos[static_cast<std::size_t>(i)];
        const double zi = z[i] / m_ic[static_cast<std::size_t>(dpos)];
        z[i] = zi;
        for (int k = m_rowPtr[static_cast<std::size_t>(i)]; k < dpos; ++k) {
            z[m_col[static_cast<std::size_t>(k)]] -= m_ic[static_cast<std::size_t>(k)] * zi;
        }
    }
}

void MpsSolver::solvePpe() {
    // Preconditioned conjugate gradient on the SPD system A x = b, warm-started.
    const std::size_t n = m_rows;
    m_stats.ppeUnknowns = n;
    m_stats.ppeIterations = 0;
    m_stats.ppeResidual = 0.0;
    if (n == 0) return;
    if (m_par.preconditioner == Preconditioner::IncompleteCholesky) factorIncompleteCholesky();
    if (m_par.preconditioner == Preconditioner::TwoLevel) setupTwoLevel();
    double* x = m_x.data();
    double* r = m_r.data();
    double* z = m_z.data();
    double* d = m_d.data();
    double* q = m_q.data();
    const double* b = m_b.data();
    const double bNorm = std::sqrt(dot(b, b, n));
    if (bNorm == 0.0) {
        std::fill(x, x + n, 0.0);
        return;
    }
    if (!std::isfinite(bNorm)) fail(m_rowParticle[0], "pressure Poisson source term is not finite");
    matVec(x, q);
#pragma omp parallel for schedule(static) if(n >= kParallelVector)
    for (std::size_t i = 0; i < n; ++i) r[i] = b[i] - q[i];
    double rNorm = std::sqrt(dot(r, r, n));
    const double target = m_par.ppeTolerance * bNorm;
    int it = 0;
    if (rNorm > target) {
        applyPreconditioner(r, z);
        std::copy(z, z + n, d);
        double rz = dot(r, z, n);
        while (it < m_par.ppeMaxIterations) {
            const double alpha = rz / matVec(d, q); // q = A d and d.q in one sweep
            double rr = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : rr) if(n >= kParallelVector)
            for (std::size_t i = 0; i < n; ++i) {
                x[i] += alpha * d[i];
                r[i] -= alpha * q[i];
                rr += r[i] * r[i];
            }
            ++it;
            rNorm = std::sqrt(rr);
            if (!(rNorm > target)) break; // also stops on NaN, caught below
            applyPreconditioner(r, z);
            const double rzNew = dot(r, z, n);
            const double beta = rzNew / rz;
            rz = rzNew;
#pragma omp parallel for schedule(static) if(n >= kParallelVector)
            for (std::size_t i = 0; i < n; ++i) d[i] = z[i] + beta * d[i];
        }
    }
    m_stats.ppeIterations = it;
    m_stats.ppeResidual = rNorm / bNorm;
    if (!std::isfinite(rNorm)) fail(m_rowParticle[0], "pressure Poisson solve produced NaN/Inf");
    if (rNorm > target) {
        std::size_t worst = 0;
        for (std::size_t i = 1; i < n; ++i) {
            if (std::abs(r[i]) > std::abs(r[worst])) worst = i;
        }
        fail(m_rowParticle[worst], fmt::format("pressure Poisson solve did not converge: relative residual {:.3g} "
                                               "after {} iterations (tolerance {:.3g}); largest residual at this "
                                               "particle", rNorm / bNorm, it, m_par.ppeTolerance));
    }
}

void MpsSolver::correctionPhase(double dt) {
    const std::size_t n = m_p.size();
    // Pressures: unknowns from the solve, negative ones cut to 0 (textbook code); surface
    // and dummy particles at 0 (K&O 1996 free-surface Dirichlet condition).
#pragma omp parallel for schedule(static) if(n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        const int r = m_row[i];
        m_p.p[i] = r >= 0 ? std::max(0.0, m_x[static_cast<std::size_t>(r)]) : 0.0;
    }
    const double reN2 = m_reN * m_reN;
    // K&O 1996 gradient model: grad p_i = d/n0 sum (p_j - p_i^min) (r_j - r_i) / r^2 w; then the
    // correction u' = -dt/rho grad p, u = u* + u', r = r* + dt u' (K&O 1996 pressure correction).
    const double coefG = kDim / m_latN.n0;
    const double k = dt / m_phys.density;
    const bool gc = m_par.gradientCorrection;
    const bool sym = m_par.symmetricGradient; // (p_i + p_j) pair term instead of (p_j - p_i^min)
    double maxSpeed2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : maxSpeed2) if(n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        if (isFixed(m_p.kind[i])) {
            m_p.x[i] = m_xStar[i]; // a moving wall's prescribed place (others unchanged)
            m_p.vx[i] = m_uStar[i];
            continue;
        }
        // Minimum pressure among neighbours within re (the K&O 1996 gradient model uses
        // p_i^min for stability); the symmetric pair term does not need it.
        double pm = m_p.p[i];
        if (!sym) {
            for (std::uint32_t j : m_grid.shortNeighbors(i)) {
                if (m_p.kind[j] == ParticleKind::Dummy) continue;
                const double dx = m_xStar[j] - m_xStar[i];
                const double dy = m_yStar[j] - m_yStar[i];
                if (dx * dx + dy * dy < reN2) pm = std::min(pm, m_p.p[j]);
            }
        }
        double gx = 0.0, gy = 0.0;
        for (std::uint32_t j : m_grid.shortNeighbors(i)) {
            if (m_p.kind[j] == ParticleKind::Dummy) continue;
            const double dx = m_xStar[j] - m_xStar[i];
            const double dy = m_yStar[j] - m_yStar[i];
            const double r2 = dx * dx + dy * dy;
            if (r2 >= reN2 || r2 <= 0.0) continue;
            const double pij = sym ? m_p.p[j] + m_p.p[i] : m_p.p[j] - pm;
            const double f = pij / r2 * mpsWeight(std::sqrt(r2), m_reN);
            gx += f * dx;
            gy += f * dy;
        }
        if (gc) {
            // Khayyer & Gotoh (2011) corrective matrix: C_i = (d/n0 sum w r_ij r_ij^T / r^2)^-1.
            double cxx = 0.0, cxy = 0.0, cyy = 0.0;
            for (std::uint32_t j : m_grid.shortNeighbors(i)) {
                if (m_p.kind[j] == ParticleKind::Dummy) continue;
                const double dx = m_xStar[j] - m_xStar[i];
                const double dy = m_yStar[j] - m_yStar[i];
                const double r2 = dx * dx + dy * dy;
                if (r2 >= reN2 || r2 <= 0.0) continue;
                const double w = mpsWeight(std::sqrt(r2), m_reN) / r2;
                cxx += w * dx * dx;
                cxy += w * dx * dy;
                cyy += w * dy * dy;
            }
            cxx *= coefG;
            cxy *= coefG;
            cyy *= coefG;
            const double det = cxx * cyy - cxy * cxy;
            // Use the correction only where the tensor is well conditioned (not for a particle
            // with neighbours on one line, e.g. a lone splash pair).
            if (det > 0.1) {
                const double hx = (cyy * gx - cxy * gy) / det;
                const double hy = (-cxy * gx + cxx * gy) / det;
                gx = hx;
                gy = hy;
            }
        }
        const double ux = -k * coefG * gx;
        const double uy = -k * coefG * gy;
        m_p.vx[i] = m_uStar[i] + ux;
        m_p.vy[i] = m_vStar[i] + uy;
        m_p.x[i] = m_xStar[i] + dt * ux;
        m_p.y[i] = m_yStar[i] + dt * uy;
        maxSpeed2 = std::max(maxSpeed2, m_p.vx[i] * m_p.vx[i] + m_p.vy[i] * m_p.vy[i]);
    }
    m_stats.maxSpeed = std::sqrt(maxSpeed2);
    m_stats.courant = m_stats.maxSpeed * dt / m_l0;
}

void MpsSolver::checkState(double dt) {
    const std::size_t n = m_p.size();
    std::size_t bad = n;    // first non-finite particle
    std::size_t out = 0;    // particles out of the domain
    std::size_t firstOut = n;
#pragma omp parallel for schedule(static) reduction(min : bad, firstOut) reduction(+ : out) if(n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        const bool finite = std::isfinite(m_p.x[i]) && std::isfinite(m_p.y[i]) && std::isfinite(m_p.vx[i]) &&
                            std::isfinite(m_p.vy[i]) && std::isfinite(m_p.p[i]);
        if (!finite) {
            bad = std::min(bad, i);
        } else if (!m_domain.contains(m_p.x[i], m_p.y[i])) {
            ++out;
            firstOut = std::min(firstOut, i);
        }
    }
    m_stats.outOfBounds = out;
    if (bad < n) {
        fail(bad, fmt::format("non-finite state: x = ({}, {}) m, u = ({}, {}) m/s, p = {} Pa", m_p.x[bad],
                              m_p.y[bad], m_p.vx[bad], m_p.vy[bad], m_p.p[bad]));
    }
    if (out > 0) {
        fail(firstOut, fmt::format("{} particle(s) left the domain [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] m; this one "
                                   "is at ({:.6g}, {:.6g}) m", out, m_domain.x0, m_domain.x1, m_domain.y0,
                                   m_domain.y1, m_p.x[firstOut], m_p.y[firstOut]));
    }
    if (m_stats.courant > m_par.courantLimit) {
        std::size_t fastest = 0;
        double best = -1.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double s = std::hypot(m_p.vx[i], m_p.vy[i]);
            if (s > best) {
                best = s;
                fastest = i;
            }
        }
        fail(fastest, fmt::format("Courant number {:.3g} = |u| dt / l0 = {:.4g} m/s x {:.4g} s / {:.4g} m exceeds "
                                  "solver.courant_limit {:.3g}", m_stats.courant, best, dt, m_l0,
                                  m_par.courantLimit));
    }
}

} // namespace swell::bake
