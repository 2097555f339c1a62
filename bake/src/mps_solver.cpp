// The semi-implicit MPS step of Koshizuka & Oka (1996) as the paper's Sec. 3.1 uses it
// (eqs. (1)-(4)), in the order MpsSolver::step() takes it:
//   1. explicit prediction: viscosity (Laplacian model) and gravity, u* = u + dt (nu lap u + g)
//      and r* = r + dt u* (the explicit part of eq. (2)); then the textbook collision model;
//   2. particle number density n* at r* and the free-surface test n* < T_s n0 (eq. (3));
//   3. the pressure Poisson equation (PPE) for the particles inside, solved by
//      pressure_solver.h;
//   4. the pressure gradient correction u = u* - dt/rho grad p, r = r* + dt (u - u*).
// Every sum over neighbours goes through forNeighbours, in neighbour-list order.
#include "swell/bake/mps_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "parallel_thresholds.h"
#include "swell/bake/error.h"

namespace swell::bake {
namespace {

constexpr double kDim = 2.0; // d in K&O's Laplacian and gradient models

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

bool isFixed(ParticleKind k) {
    return k != ParticleKind::Water;
}

/// Calls f(j, dx, dy, r2) for every neighbour j of particle i in `list`, in list order, with
/// (dx, dy) = r_j - r_i at the positions (x, y) and r2 = dx^2 + dy^2, skipping those with
/// r2 >= radius2. The list order is the order of every sum over j (so results do not
/// depend on threads).
template <class F>
inline void forNeighbours(std::span<const std::uint32_t> list, const std::vector<double>& x,
                          const std::vector<double>& y, std::size_t i, double radius2, F&& f) {
    for (std::uint32_t j : list) {
        const double dx = x[j] - x[i];
        const double dy = y[j] - y[i];
        const double r2 = dx * dx + dy * dy;
        if (r2 >= radius2)
            continue;
        f(j, dx, dy, r2);
    }
}

/// Which side of `domain` the point (x, y) outside it is on, and what that usually means.
std::string exitSide(const Box& domain, double x, double y) {
    if (y > domain.y1) {
        return "above its top: spray thrown higher than the domain reaches (geometry.domain "
               "can give it more room)";
    }
    if (y < domain.y0)
        return "below it: water that fell outside the walls or went through the bed";
    return x < domain.x0 ? "left of it" : "right of it";
}

} // namespace

std::string_view toString(Phase phase) {
    switch (phase) {
    case Phase::Neighbors:
        return "neighbors";
    case Phase::Explicit:
        return "explicit";
    case Phase::Density:
        return "density";
    case Phase::PpeAssembly:
        return "ppe_assembly";
    case Phase::PpeSolve:
        return "ppe_solve";
    case Phase::Correction:
        return "correction";
    }
    return "?";
}

std::string_view toString(Preconditioner p) {
    switch (p) {
    case Preconditioner::Jacobi:
        return "jacobi";
    case Preconditioner::SymmetricGaussSeidel:
        return "symmetric_gauss_seidel";
    case Preconditioner::IncompleteCholesky:
        return "incomplete_cholesky";
    case Preconditioner::TwoLevel:
        return "two_level";
    }
    return "?";
}

std::string_view toString(GradientModel g) {
    switch (g) {
    case GradientModel::MinimumPressure:
        return "minimum_pressure";
    case GradientModel::MinimumPressureCorrected:
        return "minimum_pressure_corrected";
    case GradientModel::Symmetric:
        return "symmetric";
    case GradientModel::SymmetricCorrected:
        return "symmetric_corrected";
    }
    return "?";
}

std::string_view toString(Scheme s) {
    return s == Scheme::Textbook ? "textbook" : "swell";
}

std::string_view toString(SurfaceTest s) {
    return s == SurfaceTest::Density ? "density" : "distribution";
}

std::string_view toString(SourceTerm s) {
    return s == SourceTerm::Relaxed ? "relaxed" : "mixed";
}

MpsSolver::MpsSolver(const PhysicsParams& physics, const SolverParams& solver, Particles particles,
                     double spacing, const Box& domain)
    : m_phys(physics), m_par(solver), m_p(std::move(particles)), m_l0(spacing), m_domain(domain) {
    const auto require = [](bool ok, const char* what) {
        if (!ok)
            throw std::invalid_argument(std::string("MpsSolver: ") + what);
    };
    const TimeStepParams& time = m_par.time;
    const ModelParams& model = m_par.model;
    const PressureParams& ppe = m_par.pressure;
    const NeighborParams& lists = m_par.neighbors;
    require(m_l0 > 0.0 && std::isfinite(m_l0), "spacing must be positive");
    require(m_phys.density > 0.0, "density must be positive");
    require(m_phys.kinematicViscosity >= 0.0, "viscosity must not be negative");
    require(time.dt > 0.0, "dt must be positive");
    require(model.reDensity > 1.0 && model.reLaplacian > 1.0,
            "kernel radii must exceed one spacing");
    require(ppe.tolerance > 0.0 && ppe.maxIterations > 0,
            "PPE tolerance and iterations must be positive");
    require(lists.skin >= 0.0 && lists.maxNeighbors > 0, "bad neighbour skin or capacity");
    require(time.courantLimit > 0.0 && time.courantTarget > 0.0,
            "Courant numbers must be positive");
    const std::size_t n = m_p.size();
    require(n > 0 && m_p.count(ParticleKind::Water) > 0, "no water particles");
    require(m_p.consistent(), "particle arrays differ in length");
    for (std::size_t i = 0; i < n; ++i) {
        if (!m_domain.contains(m_p.x[i], m_p.y[i])) {
            throw std::invalid_argument(fmt::format(
                "MpsSolver: particle {} at ({}, {}) is outside the domain", i, m_p.x[i], m_p.y[i]));
        }
    }

    m_reN = model.reDensity * m_l0;
    m_reL = model.reLaplacian * m_l0;
    m_collide = model.collisionDistance * m_l0;
    m_reP = model.rePacking * m_l0;
    m_reList = std::max({m_reN, m_reL, m_collide, m_reP}) + lists.skin * m_l0;
    // The number-density kernel (density, gradient, p_min) and the collisions reach only
    // re_N: they scan a short sub-list, half as long as the full one at the textbook radii.
    m_reShort = std::min(m_reList, std::max(m_reN, m_collide) + lists.skin * m_l0);
    m_latN = latticeConstants(m_l0, m_reN);
    m_latL = latticeConstants(m_l0, m_reL);
    if (m_reP > 0.0)
        m_latP = latticeConstants(m_l0, m_reP);
    m_grid.configure(m_domain, m_reList, n, lists.maxNeighbors);

    for (auto* v : {&m_xs, &m_ys, &m_xStar, &m_yStar, &m_uStar, &m_vStar, &m_uC, &m_vC, &m_divU,
                    &m_fx, &m_fy, &m_fNorm, &m_shiftX, &m_shiftY, &m_nPack}) {
        v->assign(n, 0.0);
    }
    m_surface.assign(n, 0);
    m_layer.assign(n, 0);
    m_row.assign(n, -1);
    m_rowParticle.assign(n, 0);
    // One PPE row per particle at most, each with room for a full neighbour list + diagonal.
    m_ppe = PressureSolver(ppe.preconditioner, ppe.tolerance, ppe.maxIterations, n,
                           static_cast<std::size_t>(lists.maxNeighbors) + 1, m_grid.cellsX(),
                           m_grid.cellsY());
    // Initial number density, so n is meaningful before the first step.
    rebuildNeighbors(m_p.x, m_p.y);
    for (std::size_t i = 0; i < n; ++i) {
        double s = 0.0;
        forNeighbours(m_grid.neighbors(i), m_p.x, m_p.y, i, std::numeric_limits<double>::infinity(),
                      [&](std::uint32_t, double dx, double dy, double) {
                          s += mpsWeight(std::hypot(dx, dy), m_reN);
                      });
        m_p.n[i] = s;
    }
}

void MpsSolver::setMovingWall(MovingWall wall) {
    const std::size_t n = m_p.size();
    if (!wall.motion)
        throw std::invalid_argument("MpsSolver::setMovingWall: no motion function");
    m_moving.assign(n, 0);
    m_restX.assign(n, 0.0);
    const double X = wall.motion(m_time).displacement;
    for (std::uint32_t i : wall.particles) {
        if (i >= n || !isFixed(m_p.kind[i])) {
            throw std::invalid_argument(
                fmt::format("MpsSolver::setMovingWall: particle {} is not a wall particle", i));
        }
        m_moving[i] = 1;
        m_restX[i] = m_p.x[i] - X;
    }
    m_wall = std::move(wall);
}

void MpsSolver::setInflow(const Box& zone, double velocity) {
    if (!std::isfinite(velocity)) {
        throw std::invalid_argument("MpsSolver::setInflow: velocity must be finite");
    }
    m_hasInflow = true;
    m_inflowZone = zone;
    m_inflowVelocity = velocity;
}

void MpsSolver::relocateWater(std::size_t i, double x, double y, double vx, double vy) {
    if (i >= m_p.size() || m_p.kind[i] != ParticleKind::Water) {
        throw std::invalid_argument(
            fmt::format("MpsSolver::relocateWater: particle {} is not water", i));
    }
    if (!m_domain.contains(x, y)) {
        throw std::invalid_argument(
            fmt::format("MpsSolver::relocateWater: ({}, {}) is outside the domain", x, y));
    }
    m_p.x[i] = x;
    m_p.y[i] = y;
    m_p.vx[i] = vx;
    m_p.vy[i] = vy;
    m_xs[i] = std::numeric_limits<double>::quiet_NaN(); // forces a neighbour rebuild next step
}

Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>> MpsSolver::ppeMatrix() const {
    const SparseRows& a = m_ppe.matrix();
    const auto rows = static_cast<Eigen::Index>(a.rows);
    int nnz = 0;
    for (std::size_t r = 0; r < a.rows; ++r)
        nnz += a.rowNnz[r];
    return {rows, rows, nnz, a.rowPtr.data(), a.col.data(), a.val.data(), a.rowNnz.data()};
}

Eigen::Map<const Eigen::VectorXd> MpsSolver::ppeRhs() const {
    return {m_ppe.rhs().data(), static_cast<Eigen::Index>(m_ppe.matrix().rows)};
}

Eigen::Map<const Eigen::VectorXd> MpsSolver::ppeSolution() const {
    return {m_ppe.solution().data(), static_cast<Eigen::Index>(m_ppe.matrix().rows)};
}

void MpsSolver::fail(std::size_t particle, const std::string& reason) const {
    // The time at the end of the (sub-)step being taken: m_time is its start.
    const int k = m_stats.substeps;
    throw DivergenceError(m_step + 1, m_time + m_stats.dt / k, particle,
                          k == 1 ? reason
                                 : fmt::format("{} (in sub-step {} of {}, "
                                               "solver.substep_courant {:.3g})",
                                               reason, m_substep, k, m_par.time.substepCourant));
}

void MpsSolver::rebuildNeighbors(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = m_p.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
            fail(i, fmt::format("non-finite position of {} particle: ({}, {}) m, velocity ({}, "
                                "{}) m/s",
                                toString(m_p.kind[i]), x[i], y[i], m_p.vx[i], m_p.vy[i]));
        }
        if (!m_domain.contains(x[i], y[i])) {
            fail(i, fmt::format("{} particle at ({:.6g}, {:.6g}) m left the domain [{:.6g}, "
                                "{:.6g}] x [{:.6g}, {:.6g}] m, {}",
                                toString(m_p.kind[i]), x[i], y[i], m_domain.x0, m_domain.x1,
                                m_domain.y0, m_domain.y1, exitSide(m_domain, x[i], y[i])));
        }
    }
    if (!m_grid.build(x, y, m_reList, m_reShort)) {
        fail(m_grid.overflowParticle(),
             fmt::format("more than {} neighbours within {:.3g} l0 (particles clumping; raise "
                         "solver.max_neighbors only if this is expected)",
                         m_par.neighbors.maxNeighbors, m_reList / m_l0));
    }
    std::copy(x.begin(), x.end(), m_xs.begin());
    std::copy(y.begin(), y.end(), m_ys.begin());
    ++m_stats.neighborRebuilds;
}

bool MpsSolver::skinUsedUp(const std::vector<double>& x, const std::vector<double>& y) const {
    // Verlet criterion: lists built with radius re + skin stay complete while no particle
    // has moved more than skin / 2 since the build.
    const double half = 0.5 * m_par.neighbors.skin * m_l0;
    const double limit2 = half * half;
    const std::size_t n = m_p.size();
    int used = 0;
#pragma omp parallel for reduction(| : used) schedule(static) if (n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        const double dx = x[i] - m_xs[i];
        const double dy = y[i] - m_ys[i];
        // A NaN displacement also counts: the rebuild then reports the particle.
        if (!(dx * dx + dy * dy <= limit2))
            used = 1;
    }
    return used != 0;
}

double MpsSolver::chooseDt() const {
    const TimeStepParams& t = m_par.time;
    if (!t.adaptive || m_stats.maxSpeed <= 0.0)
        return t.dt;
    return std::min(t.dt, t.courantTarget * m_l0 / m_stats.maxSpeed);
}

int MpsSolver::substepsFor(double dt) const {
    // Sub-steps: a fast splash (paper Figure 3's jets) is followed in k shorter steps, so
    // that no particle crosses more than substepCourant l0 per sub-step, while the step, its
    // time and the frames built on it stay as they are.
    const double c = m_par.time.substepCourant;
    const double courant = m_stats.maxSpeed * dt / m_l0;
    if (!(c > 0.0) || !(courant > c))
        return 1;
    return static_cast<int>(std::min<double>(kMaxSubsteps, std::ceil(courant / c)));
}

const StepStats& MpsSolver::step() {
    const double dt = chooseDt();
    const int k = substepsFor(dt);
    const double lastMaxSpeed = m_stats.maxSpeed;
    m_stats = StepStats{};
    m_stats.step = m_step + 1;
    m_stats.dt = dt;
    m_stats.substeps = k;
    m_stats.maxSpeed = lastMaxSpeed;
    if (k == 1) {
        m_substep = 1;
        advance(dt);
        m_time += dt;
    } else {
        const double start = m_time;
        const double h = dt / k;
        for (int s = 0; s < k; ++s) {
            m_substep = s + 1;
            m_time = start + s * h;
            advance(h);
        }
        m_time = start + dt;
    }
    ++m_step;
    m_stats.time = m_time;
    return m_stats;
}

void MpsSolver::advance(double dt) {
    PhaseTimer timer(m_stats);
    if (skinUsedUp(m_p.x, m_p.y))
        rebuildNeighbors(m_p.x, m_p.y);
    timer.lap(Phase::Neighbors);
    predictVelocity(dt); // 1. explicit: viscosity, gravity (eq. (2), explicit part)
    resolveCollisions(dt);
    timer.lap(Phase::Explicit);
    if (skinUsedUp(m_xStar, m_yStar))
        rebuildNeighbors(m_xStar, m_yStar);
    timer.lap(Phase::Neighbors);
    numberDensityAndSurface(); // 2. n* and the free surface (eq. (3))
    timer.lap(Phase::Density);
    assemblePressureEquation(dt); // 3. the PPE ...
    timer.lap(Phase::PpeAssembly);
    solvePressure(); //                 ... and its solve
    timer.lap(Phase::PpeSolve);
    correctVelocity(dt); // 4. pressure gradient correction
    if (m_par.model.shifting > 0.0)
        shiftParticles(dt);
    checkState(dt);
    timer.lap(Phase::Correction);
}

void MpsSolver::predictVelocity(double dt) {
    const std::size_t n = m_p.size();
    // K&O 1996 Laplacian model: lap u_i = 2d/(lambda n0) sum_j (u_j - u_i) w(r_ij), re = re_L.
    const double coefL = 2.0 * kDim / (m_latL.n0 * m_latL.lambda);
    const double nu = m_phys.kinematicViscosity;
    const double g = m_phys.gravity;
    const double reL2 = m_reL * m_reL;
    // Algorithm 1, step 3: move the pushing wall to its prescribed place at the end of the step.
    const PistonState wall = m_wall.motion ? m_wall.motion(m_time + dt) : PistonState{};
    const bool anyMoving = !m_moving.empty();
#pragma omp parallel for schedule(static, kParticleChunk) if (n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        if (isFixed(m_p.kind[i])) {
            const bool moving = anyMoving && m_moving[i];
            m_xStar[i] = moving ? m_restX[i] + wall.displacement : m_p.x[i];
            m_yStar[i] = m_p.y[i];
            m_uStar[i] = moving ? wall.velocity : 0.0;
            m_vStar[i] = 0.0;
            continue;
        }
        double lx = 0.0, ly = 0.0;
        forNeighbours(m_grid.neighbors(i), m_p.x, m_p.y, i, reL2,
                      [&](std::uint32_t j, double, double, double r2) {
                          const double w = mpsWeight(std::sqrt(r2), m_reL);
                          lx += (m_p.vx[j] - m_p.vx[i]) * w;
                          ly += (m_p.vy[j] - m_p.vy[i]) * w;
                      });
        // Explicit part of paper eq. (2): u* = u + dt (nu lap u + f), r* = r + dt u*.
        m_uStar[i] = m_p.vx[i] + dt * (nu * coefL * lx);
        if (m_hasInflow && m_inflowZone.contains(m_p.x[i], m_p.y[i])) {
            m_uStar[i] = m_inflowVelocity; // Sec. 3.3.2 inflow
        }
        m_vStar[i] = m_p.vy[i] + dt * (nu * coefL * ly - g);
        m_xStar[i] = m_p.x[i] + dt * m_uStar[i];
        m_yStar[i] = m_p.y[i] + dt * m_vStar[i];
    }
}

void MpsSolver::resolveCollisions(double dt) {
    // Collision model of the textbook code: a water particle approaching another closer than
    // collisionDistance loses the approaching part of its relative velocity, with restitution
    // e, as in an equal-mass impact. Gather form: each i only changes itself.
    const std::size_t n = m_p.size();
    const double c2 = m_collide * m_collide;
    const double e = m_par.model.restitution;
    std::size_t collisions = 0;
#pragma omp parallel for schedule(static, kParticleChunk) reduction(+ : collisions) if (n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        m_uC[i] = m_uStar[i];
        m_vC[i] = m_vStar[i];
        if (isFixed(m_p.kind[i]))
            continue;
        forNeighbours(m_grid.shortNeighbors(i), m_xStar, m_yStar, i, c2,
                      [&](std::uint32_t j, double dx, double dy, double r2) {
                          if (r2 <= 0.0)
                              return;
                          const double r = std::sqrt(r2);
                          const double nx = dx / r, ny = dy / r;
                          const double approach =
                              (m_uC[i] - m_uStar[j]) * nx + (m_vC[i] - m_vStar[j]) * ny;
                          if (approach > 0.0) {
                              // m_j / (m_i + m_j) = 1/2
                              const double impulse = 0.5 * (1.0 + e) * approach;
                              m_uC[i] -= impulse * nx;
                              m_vC[i] -= impulse * ny;
                              ++collisions;
                          }
                      });
    }
    m_stats.collisions += collisions;
#pragma omp parallel for schedule(static, kParticleChunk) if (n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        if (isFixed(m_p.kind[i]))
            continue;
        m_xStar[i] += (m_uC[i] - m_uStar[i]) * dt;
        m_yStar[i] += (m_vC[i] - m_vStar[i]) * dt;
        m_uStar[i] = m_uC[i];
        m_vStar[i] = m_vC[i];
    }
}

void MpsSolver::numberDensityAndSurface() {
    const std::size_t n = m_p.size();
    const double reN2 = m_reN * m_reN;
    const double threshold = m_par.model.surfaceThreshold * m_latN.n0;
    const bool mixed = m_par.pressure.sourceTerm == SourceTerm::Mixed;
    const double coefD = kDim / m_latN.n0;
    const ModelParams& model = m_par.model;
    const bool distribution = model.surfaceTest == SurfaceTest::Distribution;
    const double sparse = model.sparseThreshold * m_latN.n0;
    const double asymmetric = model.distributionThreshold * m_latN.flatSurfaceAsymmetry;
    const double fScale = 1.0 / (m_latN.n0 * m_l0);
    const bool shifting = model.shifting > 0.0;
    // With a packing kernel (re_packing) its sum takes the full list, which reaches it; the
    // short list is its sub-list in the same order, so the re_N sums below see the same
    // neighbours in the same order either way.
    const bool packing = m_reP > 0.0;
    const double reP2 = m_reP * m_reP;
    const double scan2 = std::max(reN2, reP2);
    // |f| is read by the distribution test, the packing factor's choice of full neighbourhoods
    // and the surface particles' shift: taken once here, in parallel.
    const bool norm = distribution || packing || shifting;
    std::size_t surface = 0;
#pragma omp parallel for schedule(static, kParticleChunk) reduction(+ : surface) if (n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        double s = 0.0;
        double div = 0.0;
        double fx = 0.0, fy = 0.0;
        double cx = 0.0, cy = 0.0; // concentration gradient sums (shiftParticles)
        double sP = 0.0;
        const bool shiftSums = shifting && !isFixed(m_p.kind[i]); // fixed particles never shift
        forNeighbours(
            packing ? m_grid.neighbors(i) : m_grid.shortNeighbors(i), m_xStar, m_yStar, i, scan2,
            [&](std::uint32_t j, double dx, double dy, double r2) {
                if (packing) {
                    if (r2 < reP2)
                        sP += mpsWeight(std::sqrt(r2), m_reP);
                    if (r2 >= reN2)
                        return;
                }
                const double r = std::sqrt(r2);
                const double w = mpsWeight(r, m_reN);
                s += w;       // K&O 1996 particle number density n* = sum_j w(|r*_j - r*_i|)
                fx += dx * w; // neighbour distribution (Khayyer, Gotoh & Shao 2009)
                fy += dy * w;
                if (shiftSums && r2 > 0.0) { // concentration gradient sums (shiftParticles)
                    cx += dx * w / r2;
                    cy += dy * w / r2;
                }
                if (mixed && m_p.kind[j] != ParticleKind::Dummy) {
                    // Divergence model: d/n0 sum (u_j - u_i).(r_j - r_i) / r^2 w
                    div +=
                        ((m_uStar[j] - m_uStar[i]) * dx + (m_vStar[j] - m_vStar[i]) * dy) / r2 * w;
                }
            });
        m_p.n[i] = s;
        m_nPack[i] = sP;
        m_divU[i] = coefD * div;
        m_fx[i] = fx * fScale;
        m_fy[i] = fy * fScale;
        m_fNorm[i] = norm ? std::hypot(m_fx[i], m_fy[i]) : 0.0;
        if (m_p.kind[i] == ParticleKind::Dummy) {
            m_surface[i] = kNotInPpe;
        } else {
            // Paper eq. (3), the K&O 1996 free-surface condition: free surface where
            // n* < T_s n0, p = 0 there; the distribution test also asks for a one-sided
            // neighbourhood unless the particle is sparse.
            bool free = s < threshold;
            bool oneSided = false;
            if (distribution) {
                oneSided = m_fNorm[i] > asymmetric;
                if (free && s >= sparse)
                    free = oneSided;
            }
            m_surface[i] = free ? 1 : 0;
            // The surface layer for eq. (4): the free surface and, with the distribution
            // test, every one-sided neighbourhood (a crest compressed above T_s n0 too).
            m_layer[i] = distribution && (free || oneSided) ? 1 : 0;
            surface += m_surface[i];
        }
        m_shiftX[i] = cx;
        m_shiftY[i] = cy;
    }
    m_stats.surfaceParticles = surface;
    m_packing = packing ? measurePacking() : 1.0;
}

double MpsSolver::measurePacking() const {
    // P = mean(n / n0) / mean(n_P / n0_P), n on the number-density kernel R = re_density, over
    // the water particles whose neighbourhoods are full on both kernels: off the free surface
    // and the surface layer, and with a neighbour distribution below kFullNeighbourhood (0.05,
    // under half of what a flat lattice's second row has on 2.8 l0), so rows that a surface
    // truncates do not count. On the square lattice the water starts on, P = 1; as the flow and
    // the shifting reorder it towards a hexagonal packing, P falls below 1 (about 0.984 for a
    // hexagonal packing on R = 2.8 l0 and a 3.0 l0 packing kernel), and n0 P is the density the
    // number-density kernel reads for water of the starting volume. Summed in index order: the
    // same P with any thread count.
    const std::size_t n = m_p.size();
    double sumN = 0.0, sumP = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        if (m_p.kind[i] != ParticleKind::Water || m_surface[i] != 0 || m_layer[i] != 0 ||
            m_fNorm[i] >= kFullNeighbourhood)
            continue;
        sumN += m_p.n[i];
        sumP += m_nPack[i];
    }
    if (sumN <= 0.0 || sumP <= 0.0)
        return 1.0; // no full neighbourhood (a spray of particles): aim at n0
    return (sumN / m_latN.n0) / (sumP / m_latP.n0);
}

void MpsSolver::assemblePressureEquation(double dt) {
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
    SparseRows& A = m_ppe.matrix();
    A.rows = static_cast<std::size_t>(rows);
    const double reL2 = m_reL * m_reL;
    // Each row gets room for its whole neighbour list plus the diagonal, so one pass fills
    // it; rowNnz says how much of it is used (sparse rows with small gaps).
    A.rowPtr[0] = 0;
    for (int r = 0; r < rows; ++r) {
        const std::uint32_t i = m_rowParticle[static_cast<std::size_t>(r)];
        A.rowPtr[static_cast<std::size_t>(r) + 1] = A.rowPtr[static_cast<std::size_t>(r)] +
                                                    static_cast<int>(m_grid.neighbors(i).size()) +
                                                    1;
        m_ppe.rowCells()[static_cast<std::size_t>(r)] = m_grid.cellIndex(i);
    }

    // K&O 1996 pressure Poisson equation with the Laplacian model:
    //   sum_j a w_ij (p_i - p_j) / rho + C p_i / dt^2 = RHS,  a = 2d / (lambda n0),
    // where surface neighbours (p_j = 0) only add to the diagonal, dummies are left out, and
    // the artificial compressibility C (textbook code) makes the system strictly diagonally
    // dominant, hence symmetric positive definite.
    const double a = 2.0 * kDim / (m_latL.n0 * m_latL.lambda) / m_phys.density;
    const double compress = m_par.pressure.compressibility / (dt * dt);
    const double gamma = m_par.pressure.relaxation; // per step, as the textbook code has it
    const double n0 = m_latN.n0;
    const double target = n0 * m_packing;
    const bool mixed = m_par.pressure.sourceTerm == SourceTerm::Mixed;
    std::vector<double>& b = m_ppe.rhs();
    std::vector<double>& x = m_ppe.solution();
#pragma omp parallel for schedule(static) if (static_cast <std::size_t>(rows) >= kParallelMin)
    for (int r = 0; r < rows; ++r) {
        const std::uint32_t i = m_rowParticle[static_cast<std::size_t>(r)];
        const int begin = A.rowPtr[static_cast<std::size_t>(r)];
        int pos = begin;
        int diag = -1;
        double diagValue = compress;
        forNeighbours(m_grid.neighbors(i), m_xStar, m_yStar, i, reL2,
                      [&](std::uint32_t j, double, double, double r2) {
                          if (m_surface[j] == kNotInPpe)
                              return;
                          const double c = a * mpsWeight(std::sqrt(r2), m_reL);
                          diagValue += c;
                          const int cj = m_row[j];
                          if (cj < 0)
                              return;
                          if (diag < 0 && cj > r) { // columns are sorted: the diagonal goes here
                              diag = pos++;
                          }
                          A.col[static_cast<std::size_t>(pos)] = cj;
                          A.val[static_cast<std::size_t>(pos)] = -c;
                          ++pos;
                      });
        if (diag < 0)
            diag = pos++;
        A.rowNnz[static_cast<std::size_t>(r)] = pos - begin;
        A.col[static_cast<std::size_t>(diag)] = r;
        A.val[static_cast<std::size_t>(diag)] = diagValue;
        A.diagPos[static_cast<std::size_t>(r)] = diag;
        // K&O 1996 PPE source, relaxed (textbook): gamma / dt^2 (n* - n0) / n0. Mixed
        // (Tanaka & Masunaga 2010): - div(u*) / dt + gamma / dt^2 (n* - n0) / n0, n* and n0
        // on the number-density kernel. With re_packing the target is n0 P (measurePacking),
        // the density of water that keeps its starting volume in the packing it has now.
        double rhs = gamma / (dt * dt) * (m_p.n[i] - target) / n0;
        if (mixed)
            rhs -= m_divU[i] / dt;
        b[static_cast<std::size_t>(r)] = rhs;
        x[static_cast<std::size_t>(r)] = m_p.p[i]; // warm start from the last pressure
    }
}

void MpsSolver::solvePressure() {
    m_stats.ppeUnknowns = m_ppe.matrix().rows;
    const PressureSolveResult res = m_ppe.solve();
    m_stats.ppeIterations += res.iterations;
    m_stats.ppeResidual = std::max(m_stats.ppeResidual, res.relativeResidual);
    switch (res.status) {
    case PressureSolveStatus::Converged:
        return;
    case PressureSolveStatus::NonFiniteRhs:
        fail(m_rowParticle[0], "pressure Poisson source term is not finite");
    case PressureSolveStatus::NonFinite:
        fail(m_rowParticle[0], "pressure Poisson solve produced NaN/Inf");
    case PressureSolveStatus::NotConverged:
        fail(m_rowParticle[res.worstRow],
             fmt::format("pressure Poisson solve did not converge: relative residual {:.3g} "
                         "after {} iterations (tolerance {:.3g}); largest residual at this "
                         "particle",
                         res.relativeResidual, res.iterations, m_par.pressure.tolerance));
    }
}

void MpsSolver::correctVelocity(double dt) {
    const std::size_t n = m_p.size();
    // Pressures: unknowns from the solve, negative ones cut to 0 (textbook code); surface
    // and dummy particles at 0 (K&O 1996 free-surface Dirichlet condition).
    const std::vector<double>& solution = m_ppe.solution();
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        const int r = m_row[i];
        m_p.p[i] = r >= 0 ? std::max(0.0, solution[static_cast<std::size_t>(r)]) : 0.0;
    }
    const double reN2 = m_reN * m_reN;
    // K&O 1996 gradient model: grad p_i = d/n0 sum (p_j - p_i^min) (r_j - r_i) / r^2 w; then
    // the correction u' = -dt/rho grad p, u = u* + u', r = r* + dt u'.
    const double coefG = kDim / m_latN.n0;
    const double k = dt / m_phys.density;
    const GradientModel model = m_par.model.gradient;
    const bool corrected = usesCorrectiveMatrix(model);
    const bool symmetric = usesSymmetricPairs(model);
    const bool minimum = usesMinimumPressure(model);
    double maxSpeed2 = 0.0;
#pragma omp parallel for schedule(static, kParticleChunk)                                          \
    reduction(max                                                                                  \
              : maxSpeed2) if (n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        if (isFixed(m_p.kind[i])) {
            m_p.x[i] = m_xStar[i]; // a moving wall's prescribed place (others unchanged)
            m_p.vx[i] = m_uStar[i];
            continue;
        }
        const auto shortList = m_grid.shortNeighbors(i);
        // Minimum pressure among neighbours within re (the K&O 1996 gradient model uses
        // p_i^min for stability); the other pair terms do not need it.
        double pm = m_p.p[i];
        if (minimum) {
            forNeighbours(shortList, m_xStar, m_yStar, i, reN2,
                          [&](std::uint32_t j, double, double, double) {
                              if (m_p.kind[j] == ParticleKind::Dummy)
                                  return;
                              pm = std::min(pm, m_p.p[j]);
                          });
        }
        // gx, gy: the pair sum; cxx..cyy: the corrective matrix's moment tensor.
        double gx = 0.0, gy = 0.0;
        double cxx = 0.0, cxy = 0.0, cyy = 0.0;
        const double base = minimum ? pm : (symmetric ? -m_p.p[i] : m_p.p[i]);
        forNeighbours(shortList, m_xStar, m_yStar, i, reN2,
                      [&](std::uint32_t j, double dx, double dy, double r2) {
                          if (m_p.kind[j] == ParticleKind::Dummy || r2 <= 0.0)
                              return;
                          const double wr = mpsWeight(std::sqrt(r2), m_reN);
                          const double f = (m_p.p[j] - base) / r2 * wr;
                          gx += f * dx;
                          gy += f * dy;
                          if (!corrected)
                              return;
                          const double w = wr / r2;
                          cxx += w * dx * dx;
                          cxy += w * dx * dy;
                          cyy += w * dy * dy;
                      });
        if (corrected) {
            // Khayyer & Gotoh (2011) corrective matrix:
            // C_i = (d/n0 sum w r_ij r_ij^T / r^2)^-1.
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
    m_stats.courant = std::max(m_stats.courant, m_stats.maxSpeed * dt / m_l0);
}

void MpsSolver::shiftParticles(double dt) {
    // Particle shifting (Xu et al. 2009; Lind et al. 2012's Fickian form in MPS operators):
    // dr = -C l0^2 grad c with grad c_i = 2d/n0 sum_j (r_j - r_i) / r^2 w (the gradient of a
    // uniform concentration, zero on a regular lattice), so crowded particles spread out. The
    // pair sums were taken at r* with the number density (numberDensityAndSurface).
    // Free-surface particles move only along the surface (the normal is minus their
    // neighbour distribution), so shifting neither lifts nor sinks the surface.
    const std::size_t n = m_p.size();
    const double c = m_par.model.shifting; // per step, as the relaxation
    const double d = c * m_l0 * m_l0 * 2.0 * kDim / m_latN.n0;
    const double maxShift = 0.2 * m_l0;
    const bool damp = m_par.model.shiftDamping;
#pragma omp parallel for schedule(static, kParticleChunk) if (n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        if (isFixed(m_p.kind[i]))
            continue;
        double sx = -d * m_shiftX[i], sy = -d * m_shiftY[i];
        const bool surface = m_surface[i] == 1;
        if (surface) {
            const double fn = m_fNorm[i]; // |f| (numberDensityAndSurface)
            if (fn > 0.0) {
                const double nx = -m_fx[i] / fn, ny = -m_fy[i] / fn;
                const double along = sx * nx + sy * ny;
                sx -= along * nx;
                sy -= along * ny;
            } else {
                sx = sy = 0.0;
            }
        }
        const double len = std::hypot(sx, sy);
        if (len > maxShift) {
            sx *= maxShift / len;
            sy *= maxShift / len;
        }
        if (damp && surface)
            dampAgainstShift(i, sx, sy, std::min(len, maxShift), dt);
        m_p.x[i] += sx;
        m_p.y[i] += sy;
    }
}

void MpsSolver::dampAgainstShift(std::size_t i, double sx, double sy, double len, double dt) {
    // solver.shift_damping (docs/validation.md, Still tank). On the free surface the shift holds
    // the particles evenly spaced along it, while the pressure of the rows below can push a
    // particle along it steadily: the shift then moves it back every step and its velocity
    // grows to a value that moves it nowhere. u_s = u . s/|s| < 0 is its velocity against the
    // shift, |s| / (|u_s| dt) the part of that motion the shift cancels, and rho = min(1,
    // g |s| / (|u_s| dt)) with g = shift_damping_gain;
    // u_s -> u_s (1 - rho^3) takes all of it from a particle the shift holds in place (or, at
    // g = 2, undoes at least half of) and almost none from one the shift barely slows (a
    // surge's front, a wave's crest).
    if (!(len > 0.0))
        return;
    const double ex = sx / len, ey = sy / len;
    const double against = -(m_p.vx[i] * ex + m_p.vy[i] * ey); // -u_s
    if (!(against > 0.0))
        return;
    const double gain = m_par.model.shiftDampingGain;
    const double rho = std::min(1.0, gain * len / (against * dt));
    const double take = against * rho * rho * rho;
    m_p.vx[i] += take * ex;
    m_p.vy[i] += take * ey;
}

std::string MpsSolver::courantAdvice() const {
    // What the user can do about a step stopped on the Courant limit (docs/scenes.md,
    // solver.courant_limit and solver.substep_courant).
    const TimeStepParams& t = m_par.time;
    if (m_stats.substeps > 1 || (t.substepCourant > 0.0 && t.courantLimit > t.substepCourant)) {
        return "the flow sped up faster than the sub-steps follow: a diverging simulation, or "
               "a solver.dt too large for this flow";
    }
    if (!(t.substepCourant > 0.0)) {
        return "a smaller solver.dt, or solver.substep_courant > 0 with solver.courant_limit "
               "above it so that fast spray is followed in sub-steps";
    }
    return fmt::format("sub-steps (solver.substep_courant {:.3g}) act only under a higher "
                       "limit: raise solver.courant_limit (default {:.3g}) above it so "
                       "that fast spray is followed in sub-steps, or take a smaller "
                       "solver.dt",
                       t.substepCourant, TimeStepParams{}.courantLimit);
}

void MpsSolver::checkState(double dt) {
    const std::size_t n = m_p.size();
    std::size_t bad = n; // first non-finite particle
    std::size_t out = 0; // particles out of the domain
    std::size_t firstOut = n;
#pragma omp parallel for schedule(static) reduction(min : bad, firstOut) reduction(+ : out) if(n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
        const bool finite = std::isfinite(m_p.x[i]) && std::isfinite(m_p.y[i]) &&
                            std::isfinite(m_p.vx[i]) && std::isfinite(m_p.vy[i]) &&
                            std::isfinite(m_p.p[i]);
        if (!finite) {
            bad = std::min(bad, i);
        } else if (!m_domain.contains(m_p.x[i], m_p.y[i])) {
            ++out;
            firstOut = std::min(firstOut, i);
        }
    }
    m_stats.outOfBounds = out;
    if (bad < n) {
        fail(bad, fmt::format("non-finite state: x = ({}, {}) m, u = ({}, {}) m/s, p = {} Pa",
                              m_p.x[bad], m_p.y[bad], m_p.vx[bad], m_p.vy[bad], m_p.p[bad]));
    }
    if (out > 0) {
        fail(firstOut,
             fmt::format(
                 "{} particle(s) left the domain [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] m; this one "
                 "is at ({:.6g}, {:.6g}) m, {}",
                 out, m_domain.x0, m_domain.x1, m_domain.y0, m_domain.y1, m_p.x[firstOut],
                 m_p.y[firstOut], exitSide(m_domain, m_p.x[firstOut], m_p.y[firstOut])));
    }
    if (m_stats.courant > m_par.time.courantLimit) {
        std::size_t fastest = 0;
        double best = -1.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double s = std::hypot(m_p.vx[i], m_p.vy[i]);
            if (s > best) {
                best = s;
                fastest = i;
            }
        }
        fail(fastest,
             fmt::format(
                 "Courant number {:.3g} = |u| dt / l0 = {:.4g} m/s x {:.4g} s / {:.4g} m exceeds "
                 "solver.courant_limit {:.3g}; {}",
                 m_stats.courant, best, dt, m_l0, m_par.time.courantLimit, courantAdvice()));
    }
}

} // namespace swell::bake
