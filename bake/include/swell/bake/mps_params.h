#pragma once
#include <string_view>

namespace swell::bake {

/// Fluid properties (paper Table 1).
struct PhysicsParams {
    double density = 1000.0;           ///< rho (kg/m^3): water (paper Table 1)
    /// nu (m^2/s): paper Table 1 value, as DESIGN.md fixes the defaults (about 1,100 times real
    /// water's 1e-6, which validation scenes against experiments set explicitly).
    double kinematicViscosity = 0.0011;
    double gravity = 9.81;             ///< g (m/s^2), acting along -y (paper Table 1)
};

/// Preconditioner of the conjugate-gradient pressure solve.
enum class Preconditioner {
    Jacobi,                 ///< diagonal: parallel, weakest
    SymmetricGaussSeidel,   ///< (D+L) D^-1 (D+L)^T: no set-up, serial sweeps
    IncompleteCholesky,     ///< IC(0) on A's pattern: strong per iteration, serial set-up each step
    /// Additive two-level: Jacobi plus an exact coarse solve on aggregates (one per grid cell,
    /// piecewise constant), which removes the smooth error modes Jacobi cannot reach.
    TwoLevel,
};
/// Source term of the pressure Poisson equation.
enum class SourceTerm {
    /// K&O 1996 density-based source, relaxed as in the textbook code: gamma/dt^2 (n* - n0)/n0.
    Relaxed,
    /// Tanaka & Masunaga 2010 mixed source: rho/dt div(u*) + gamma rho/dt^2 (n* - n0)/n0 (sign per PPE).
    Mixed,
};

std::string_view toString(Preconditioner p);
std::string_view toString(SourceTerm s);

/// Numerical settings of the semi-implicit MPS solver. Radii are in units of l0.
struct SolverParams {
    double dt = 0.001;              ///< time step (s), the largest one when adaptive (paper Table 1)
    double endTime = 1.0;           ///< simulated time to run (s)
    bool adaptiveDt = false;        ///< shrink dt so max|u| dt / l0 <= courantTarget
    double courantTarget = 0.2;     ///< Courant number the adaptive step aims at (-)
    double courantLimit = 0.5;      ///< detector: a step above this Courant number stops the run (-)
    /// Speed (m/s) the scene is expected to reach, used to check dt at load; 0: 2 sqrt(g H) with
    /// H the highest water top above the lowest water bottom (dam-break front speed, Ritter).
    double expectedSpeed = 0.0;
    double reDensity = 2.1;         ///< re for number density and gradient (l0): textbook code
    double reLaplacian = 3.1;       ///< re for the Laplacian (viscosity, PPE) (l0): textbook code
    double surfaceThreshold = 0.97; ///< beta: n* < beta n0 is free surface, p = 0 (paper eq. (3))
    double relaxation = 0.2;        ///< gamma: relaxation of the PPE source term (textbook code)
    double compressibility = 0.45e-9; ///< artificial compressibility (1/Pa): textbook code, keeps PPE SPD
    double collisionDistance = 0.5; ///< pairs closer than this (l0) collide (textbook code)
    double restitution = 0.2;       ///< coefficient of restitution of collisions (-), textbook code
    SourceTerm sourceTerm = SourceTerm::Relaxed; ///< PPE right-hand side
    /// Khayyer & Gotoh (2011) corrected gradient: multiply the pressure gradient by the inverse
    /// of d/n0 sum w r_ij (x) r_ij / r^2, which is the identity on a full lattice and corrects
    /// truncated (surface, wall) neighbourhoods.
    bool gradientCorrection = false;
    Preconditioner preconditioner = Preconditioner::TwoLevel; ///< PCG preconditioner (fastest measured, docs/BENCHMARKS.md)
    double ppeTolerance = 1e-6;     ///< relative residual |b - Ax| / |b| at which PCG stops (-)
    int ppeMaxIterations = 2000;    ///< PCG iterations before the step is declared unconverged
    double neighborSkin = 0.4;      ///< Verlet skin (l0): lists are rebuilt when a particle moves skin/2
    int maxNeighbors = 96;          ///< capacity of a neighbour list; more stops the run (clumping)
};

} // namespace swell::bake
