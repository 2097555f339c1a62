#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Sparse>

#include "swell/bake/box.h"
#include "swell/bake/kernel.h"
#include "swell/bake/mps_params.h"
#include "swell/bake/mps_state.h"
#include "swell/bake/neighbor_grid.h"
#include "swell/bake/particles.h"
#include "swell/bake/piston_motion.h"
#include "swell/bake/pressure_solver.h"
#include "swell/bake/step_stats.h"

namespace swell::bake {

/// A rigid set of fixed (wall and dummy) particles moved along x with a prescribed motion:
/// a piston wavemaker (paper Sec. 3.3.1; Algorithm 1, step 3 "Move pushing wall").
struct MovingWall {
    std::vector<std::uint32_t> particles; ///< indices of Wall/Dummy particles moved together
    /// Displacement (m, along +x from the rest position) and velocity (m/s) at time t (s);
    /// must be a pure function of t (a resumed run gets the same motion).
    std::function<PistonState(double)> motion;
};

/// Semi-implicit 2D MPS solver (Koshizuka & Oka 1996; the paper's Sec. 3.1, eqs. (1)-(4)).
/// Advances plain particle arrays; no I/O. All buffers are sized at construction,
/// so step() allocates nothing. Loops over particles run in OpenMP threads.
class MpsSolver {
public:
    /// Takes the particles (water, wall, dummy) of a scene. `spacing` is l0 (m); the
    /// standard number densities n0 and lambda come from a perfect lattice of that
    /// spacing. Throws std::invalid_argument for unusable parameters or no water.
    MpsSolver(const PhysicsParams& physics, const SolverParams& solver, Particles particles,
              double spacing, const Box& domain);

    /// One time step. Throws DivergenceError (naming step, time, particle and cause)
    /// when the new state contains NaN/Inf, the PPE did not converge, the Courant number
    /// exceeds the limit, a particle left the domain, or a neighbour list overflowed.
    const StepStats& step();

    /// Makes `wall.particles` move rigidly: each step they are placed at rest + X(t + dt) with
    /// velocity V(t + dt) (which viscosity and collisions see), taking part in the pressure
    /// solve as walls. The rest positions are the current ones minus X(time()). Throws
    /// std::invalid_argument for a water particle or an index out of range.
    void setMovingWall(MovingWall wall);

    /// Inflow (paper Sec. 3.3.2, inflow-outflow scheme): water inside `zone` gets the
    /// horizontal velocity `velocity` (m/s) in the explicit phase of every step.
    void setInflow(const Box& zone, double velocity);

    /// Moves water particle i to (x, y) with velocity (vx, vy) between steps (inflow-outflow
    /// recycling, paper Sec. 3.3.2). Throws std::invalid_argument for a fixed particle or a
    /// position outside the domain.
    void relocateWater(std::size_t i, double x, double y, double vx, double vy);

    /// Takes water particles out of the simulation between steps (water that left an open tank
    /// over its walls, spill.h). The others keep their order, so every later index moves down
    /// by the number removed before it (the moving wall's indices follow). Throws
    /// std::invalid_argument for an index out of range, a fixed particle, a repeated index, or
    /// when no water would remain.
    void removeWater(std::span<const std::size_t> indices);
    /// Indices in the solver's initial particles of the water removed so far, ascending.
    const std::vector<std::uint32_t>& removedWater() const { return m_removed; }

    /// Everything a later step depends on (checkpoints); see mps_state.h.
    MpsState exportState() const;
    /// Continues from a state exported by a solver of the same scene (same particles, kinds
    /// and moving wall; set the moving wall and inflow first, as makeSolver does). Water the
    /// exporting solver had removed is removed here first. The next step then gives bit for
    /// bit what the exporting solver's next step gave. Throws std::invalid_argument (naming
    /// what differs) for a state of other particles.
    void importState(const MpsState& state);

    const Particles& particles() const { return m_p; }
    double time() const { return m_time; }
    long stepCount() const { return m_step; }
    double spacing() const { return m_l0; }
    const Box& domain() const { return m_domain; }
    const PhysicsParams& physics() const { return m_phys; }
    const SolverParams& params() const { return m_par; }
    /// Lattice constants for re = reDensity (n0 used for density, gradient, surface test).
    const LatticeConstants& densityConstants() const { return m_latN; }
    /// The PPE matrix of the last step, -Laplacian/rho + compressibility/dt^2 (rows in
    /// neighbour-grid order), as an Eigen view of the solver's buffers (for tests).
    Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor, int>> ppeMatrix() const;
    /// Right-hand side of the last PPE (for tests).
    Eigen::Map<const Eigen::VectorXd> ppeRhs() const;
    /// Solution of the last PPE before negative pressures were cut to 0 (for tests).
    Eigen::Map<const Eigen::VectorXd> ppeSolution() const;
    /// The packing factor P the last step's density term aimed at, n0 P (1 without
    /// re_packing; ModelParams::rePacking).
    double packingFactor() const { return m_packing; }
    /// Free-surface flags of the last step (1 = p fixed at 0).
    const std::vector<std::uint8_t>& surfaceFlags() const { return m_surface; }
    /// Surface-layer flags of the last step for the classification of eq. (4) (1 = on the
    /// layer: free surface or a one-sided neighbourhood); empty unless the surface test is
    /// SurfaceTest::Distribution, and all 0 before the first step.
    std::span<const std::uint8_t> surfaceLayer() const {
        if (m_par.model.surfaceTest != SurfaceTest::Distribution)
            return {};
        return m_layer;
    }

private:
    /// m_surface value of a particle outside the pressure solve (dummies).
    static constexpr std::uint8_t kNotInPpe = 2;

    void rebuildNeighbors(const std::vector<double>& x, const std::vector<double>& y);
    bool skinUsedUp(const std::vector<double>& x, const std::vector<double>& y) const;
    void predictVelocity(double dt);
    void resolveCollisions(double dt);
    void numberDensityAndSurface();
    double measurePacking() const;
    void assemblePressureEquation(double dt);
    void solvePressure();
    void correctVelocity(double dt);
    /// What a user can change when a step exceeds solver.courant_limit (the detector's message).
    std::string courantAdvice() const;
    /// solver.shift_damping: takes from free-surface particle i the velocity its shift
    /// (sx, sy), of length len, undoes in a step of dt.
    void dampAgainstShift(std::size_t i, double sx, double sy, double len, double dt);
    void shiftParticles(double dt);
    void checkState(double dt);
    double chooseDt() const;
    int substepsFor(double dt) const;
    void advance(double dt); // one (sub-)step of dt from m_time
    [[noreturn]] void fail(std::size_t particle, const std::string& reason) const;

    PhysicsParams m_phys;
    SolverParams m_par;
    Particles m_p;
    double m_l0;
    Box m_domain;
    LatticeConstants m_latN;
    LatticeConstants m_latL;
    LatticeConstants m_latP; // re = rePacking (when set)
    double m_reN, m_reL, m_reList, m_reShort, m_collide;
    double m_reP;           // the packing kernel's radius (m), 0 when off
    double m_packing = 1.0; // P of the last step: the density term aims at n0 P
    double m_time = 0.0;
    long m_step = 0;
    int m_substep = 0; // the sub-step being taken, 1-based, of m_stats.substeps (messages)
    StepStats m_stats;
    NeighborGrid m_grid;

    // work arrays (structure of arrays, sized once)
    std::vector<double> m_xs, m_ys;                         // positions at the last neighbour build
    std::vector<double> m_xStar, m_yStar, m_uStar, m_vStar; // predicted state
    std::vector<double> m_divU;     // velocity divergence (mixed source term)
    std::vector<double> m_fx, m_fy; // neighbour distribution / (n0 l0) at r*
    std::vector<double> m_fNorm;    // its length |(m_fx, m_fy)|, where a test or shift reads it
    std::vector<double> m_nPack;    // number density at r* on m_reP (when set)
    std::vector<double> m_shiftX, m_shiftY; // shifting: sum (r_j - r_i) / r^2 w at r*
    std::vector<std::uint8_t> m_surface;    // 1 free surface (p = 0), 0 inside, kNotInPpe
    std::vector<std::uint8_t> m_layer;      // 1 on the surface layer (classification)
    std::vector<std::int32_t> m_row;        // PPE row of each particle, -1 if none
    std::vector<std::uint32_t> m_rowParticle;

    std::vector<double> m_uC, m_vC;     // velocities after collisions
    MovingWall m_wall;                  // prescribed-motion wall (piston), may be empty
    std::vector<std::uint8_t> m_moving; // 1 for particles of m_wall
    std::vector<double> m_restX;        // rest x of moving-wall particles
    bool m_hasInflow = false;
    Box m_inflowZone;
    double m_inflowVelocity = 0.0;

    // The pressure Poisson equation: rows in neighbour-grid order, each with room for its
    // particle's neighbour list (pressure_solver.h).
    PressureSolver m_ppe;

    std::vector<std::uint32_t> m_removed; // initial indices of the water removed, ascending
};

} // namespace swell::bake
