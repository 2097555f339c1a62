#pragma once
#include <string_view>

namespace swell::bake {

/// Fluid properties (paper Table 1).
struct PhysicsParams {
    double density = 1000.0; ///< rho (kg/m^3): water (paper Table 1)
    /// nu (m^2/s): the paper's Table 1 value, the project's default (about 1,100 times real
    /// water's 1e-6, which validation scenes against experiments set explicitly).
    double kinematicViscosity = 0.0011;
    double gravity = 9.81; ///< g (m/s^2), acting along -y (paper Table 1)
};

/// Preconditioner of the conjugate-gradient pressure solve.
enum class Preconditioner {
    Jacobi,               ///< diagonal: parallel, weakest
    SymmetricGaussSeidel, ///< (D+L) D^-1 (D+L)^T: no set-up, serial sweeps
    IncompleteCholesky,   ///< IC(0) on A's pattern: strong per iteration, serial set-up each step
    /// Additive two-level: Jacobi plus an exact coarse solve on aggregates (one per grid cell,
    /// piecewise constant), which removes the smooth error modes Jacobi cannot reach.
    TwoLevel,
};
/// Source term of the pressure Poisson equation.
enum class SourceTerm {
    /// K&O 1996 density-based source, relaxed as in the textbook code: gamma/dt^2 (n* - n0)/n0.
    Relaxed,
    /// Tanaka & Masunaga 2010 mixed source: rho/dt div(u*) + gamma rho/dt^2 (n* - n0)/n0 (sign
    /// per PPE).
    Mixed,
};
/// Pressure gradient model of the correction step (scene keys solver.symmetric_gradient and
/// solver.gradient_correction, which combine freely).
enum class GradientModel {
    /// K&O 1996: d/n0 sum (p_j - p_i^min) r_ij / r^2 w, the textbook form.
    MinimumPressure,
    /// MinimumPressure times the Khayyer & Gotoh (2011) corrective matrix (the inverse of
    /// d/n0 sum w r_ij (x) r_ij / r^2, the identity on a full lattice), which corrects
    /// truncated (surface, wall) neighbourhoods.
    MinimumPressureCorrected,
    /// Symmetric pair term (p_i + p_j): momentum-conserving, always repulsive; damps the
    /// still-tank churn but reads the bed pressure high (docs/validation.md, "Still tank").
    Symmetric,
    /// Symmetric with the Khayyer & Gotoh corrective matrix.
    SymmetricCorrected,
};
/// Whether `g` uses the symmetric (p_i + p_j) pair term.
constexpr bool usesSymmetricPairs(GradientModel g) {
    return g == GradientModel::Symmetric || g == GradientModel::SymmetricCorrected;
}
/// Whether `g` needs the minimum neighbour pressure p_i^min.
constexpr bool usesMinimumPressure(GradientModel g) {
    return g == GradientModel::MinimumPressure || g == GradientModel::MinimumPressureCorrected;
}
/// Whether `g` applies the Khayyer & Gotoh corrective matrix.
constexpr bool usesCorrectiveMatrix(GradientModel g) {
    return g == GradientModel::MinimumPressureCorrected || g == GradientModel::SymmetricCorrected;
}
/// The model of the two scene switches.
constexpr GradientModel gradientModel(bool symmetric, bool corrected) {
    if (symmetric)
        return corrected ? GradientModel::SymmetricCorrected : GradientModel::Symmetric;
    return corrected ? GradientModel::MinimumPressureCorrected : GradientModel::MinimumPressure;
}

/// Free-surface test of the pressure solve (particles that pass get p = 0).
enum class SurfaceTest {
    /// Paper eq. (3), K&O 1996: n* < T_s n0.
    Density,
    /// n* < T_s n0 and, unless the particle is sparse (n* < sparseThreshold n0), an
    /// asymmetric neighbourhood: |sum_j (r_j - r_i) w| / (n0 l0) above distributionThreshold
    /// times that of a flat lattice surface (Khayyer, Gotoh & Shao 2009's auxiliary
    /// condition). Interior particles whose n* dips below T_s n0 keep their pressure.
    Distribution,
};

std::string_view toString(Preconditioner p);
std::string_view toString(SurfaceTest s);
std::string_view toString(GradientModel g);
std::string_view toString(SourceTerm s);

/// A named set of model and pressure-solve settings (scene key solver.scheme); individual
/// solver keys still override it. docs/validation.md measures both on every case.
enum class Scheme {
    /// Koshizuka & Oka 1996 as the textbook code has it: minimum-pressure gradient, free
    /// surface by number density alone (paper eq. (3)). Kept for comparison.
    Textbook,
    /// The default: the Khayyer & Gotoh (2011) corrected gradient (first-order consistent on
    /// truncated neighbourhoods: surface, walls); the neighbour-distribution free-surface
    /// test, which keeps interior particles whose n* dips below T_s n0 in the pressure solve
    /// and finds the whole surface layer for the classification of eq. (4); the mixed source
    /// (Tanaka & Masunaga 2010) with gamma = 0.02 and particle shifting C = 0.02 (Lind et al.
    /// 2012), so the density noise of a disordered particle set is not turned into velocity;
    /// fully inelastic collisions from 0.8 l0; the number density, gradient, surface test,
    /// shifting and collisions on a 2.8 l0 kernel; the density term aimed at n0 times the
    /// packing factor read on 3.0 l0.
    Swell,
};
std::string_view toString(Scheme s);

/// Time stepping.
struct TimeStepParams {
    double dt = 0.001;          ///< time step (s), the largest one when adaptive (paper Table 1)
    bool adaptive = false;      ///< shrink dt so max|u| dt / l0 <= courantTarget
    double courantTarget = 0.2; ///< Courant number the adaptive step aims at (-)
    /// Detector: a step (or sub-step) above this Courant number stops the run; also the
    /// load-time check of dt at the scene's expected speed (-). Above substepCourant, so that
    /// a flow speeding up is first taken in sub-steps and only stopped when a sub-step still
    /// outruns it (with both at 0.5, a step that would be split
    /// had already been stopped, and every splashing scene had to raise it).
    double courantLimit = 0.8;
    /// A step whose Courant number, max|u| of the previous step x dt / l0, is above this is
    /// taken as k = ceil(C / substepCourant) equal sub-steps (at most kMaxSubsteps), so a fast
    /// splash is followed in finer steps while frames stay evenly spaced; 0 turns it off (-).
    double substepCourant = 0.5;
};

/// Most sub-steps one step is split into (TimeStepParams::substepCourant); a flow that needs
/// more is stopped by the detector's Courant limit.
inline constexpr int kMaxSubsteps = 64;

/// The particle model: kernel radii (in l0), free-surface test, collisions, gradient model.
struct ModelParams {
    double reDensity = 2.1;   ///< re for number density and gradient (l0): textbook code
    double reLaplacian = 3.1; ///< re for the Laplacian (viscosity, PPE) (l0): textbook code
    /// re (l0) of the kernel that reads how the particles are packed; 0 turns it off. When
    /// set, the density term aims at n0 P instead of n0, with one P for the whole particle set:
    /// the mean of n / n0 on the relaxation's kernel over the mean on this one, over the water
    /// particles with full neighbourhoods (packingFactor). On a kernel on which a hexagonal and
    /// a square packing reach their n0 in the same area (3.0 l0), the water then keeps the
    /// volume it started with when the flow reorders it, while every local density error is
    /// still read on the relaxation's kernel.
    double rePacking = 0.0;
    double surfaceThreshold = 0.97; ///< T_s: n* < T_s n0 is free surface, p = 0 (eq. (3)'s beta)
    double collisionDistance = 0.5; ///< pairs closer than this (l0) collide (textbook code)
    double restitution = 0.2;       ///< coefficient of restitution of collisions (-), textbook code
    GradientModel gradient = GradientModel::MinimumPressure; ///< pressure gradient model
    SurfaceTest surfaceTest = SurfaceTest::Density;          ///< free-surface test
    double sparseThreshold = 0.8; ///< Distribution test: n* below this (n0) is surface anyway
    /// Distribution test: |F| above this fraction of a flat surface's |F| is surface (-).
    double distributionThreshold = 0.5;
    /// Particle shifting coefficient C (-): after each step water moves by
    /// -C l0^2 grad c (c the particle concentration, MPS gradient over re_N), only along the
    /// surface on free-surface particles (Lind et al. 2012); 0 turns shifting off.
    double shifting = 0.0;
    /// With shifting: the velocity a free-surface particle's shift undoes is taken from it.
    /// Its shift s runs along the surface; where its velocity along s, u_s = u . s/|s|, is
    /// negative (the shift moves it back against its own motion), rho = min(1, |s| /
    /// (|u_s| dt)) is the part of that motion the shift cancels, and u_s becomes
    /// u_s (1 - rho^3): a particle held in place keeps no velocity along the surface, one
    /// that the shift barely slows keeps nearly all. Dissipative only: |u| never grows.
    bool shiftDamping = false;
    /// With shift_damping: the gain g on the part of the motion the shift cancels, rho =
    /// min(1, g |s| / (|u_s| dt)). At g = 1 (both schemes) the damping lets go as soon as the
    /// velocity carries a particle further per step than its shift; at g = 2 it takes all of
    /// it while the shift undoes at least half the motion, so a particle the wall's pressure
    /// pushes against its shift is not released in bursts. A crest
    /// or a surge front the shift slows by a tenth keeps 1 - (g/10)^3 of its motion.
    double shiftDampingGain = 1.0;
};

/// A neighbour distribution |f| (numberDensityAndSurface, in units of n0 l0) below this is a
/// full neighbourhood: under half of what a flat lattice's second row has on 2.8 l0 (0.123;
/// tools/packing_density.py), so rows that a surface truncates are above it.
inline constexpr double kFullNeighbourhood = 0.05;

/// The pressure Poisson equation and its conjugate-gradient solve.
struct PressureParams {
    SourceTerm sourceTerm = SourceTerm::Relaxed; ///< PPE right-hand side
    double relaxation = 0.2; ///< gamma: relaxation of the PPE source term (textbook code)
    /// Artificial compressibility (1/Pa): textbook code, keeps the PPE matrix SPD.
    double compressibility = 0.45e-9;
    /// PCG preconditioner (the fastest measured: docs/BENCHMARKS.md).
    Preconditioner preconditioner = Preconditioner::TwoLevel;
    double tolerance = 1e-6;  ///< relative residual |b - Ax| / |b| at which PCG stops (-)
    int maxIterations = 2000; ///< PCG iterations before the step is declared unconverged
};

/// Neighbour lists.
struct NeighborParams {
    double skin = 0.4;     ///< Verlet skin (l0): lists are rebuilt when a particle moves skin/2
    int maxNeighbors = 96; ///< capacity of a neighbour list; more stops the run (clumping)
};

/// The swell scheme's model and pressure settings: the textbook scheme (the member defaults of
/// ModelParams and PressureParams, Koshizuka & Oka 1996) with these changes.
inline void applySwellScheme(ModelParams& m, PressureParams& q) {
    m.gradient = GradientModel::MinimumPressureCorrected;
    m.surfaceTest = SurfaceTest::Distribution;
    // The mixed source projects u* to zero divergence and keeps only a small density
    // relaxation, so density noise of a disordered particle set is not kicked into the
    // velocity every step; shifting keeps the particle set ordered instead. Collisions
    // from 0.8 l0, fully inelastic, keep dam-break impacts stable under that source.
    q.sourceTerm = SourceTerm::Mixed;
    q.relaxation = 0.02;
    m.shifting = 0.02;
    // A surface particle the shift holds against its own motion keeps no velocity along
    // the surface: otherwise the still tank's top row carries speeds that move it nowhere
    // (docs/validation.md, "Still tank").
    m.shiftDamping = true;
    // shiftDampingGain stays at 1: a higher gain makes the standing and travelling waves
    // decay faster (docs/validation.md, "What was tried").
    m.collisionDistance = 0.8;
    m.restitution = 0.0;
    // A wider number-density kernel than the textbook 2.1 l0: 2.8 l0 reaches the lattice
    // shell at sqrt(5) l0 (not the one at sqrt(8) l0, as the Laplacian's 3.1 l0 does),
    // and measured across every validation case it keeps progressive waves from decaying.
    m.reDensity = 2.8;
    // The packing factor read on 3.0 l0 (a hexagonal packing holds n0 in the square
    // lattice's area there) keeps the still tank's volume with the density term on 2.8 l0.
    m.rePacking = 3.0;
}

inline ModelParams swellModel() {
    ModelParams m;
    PressureParams q;
    applySwellScheme(m, q);
    return m;
}

inline PressureParams swellPressure() {
    ModelParams m;
    PressureParams q;
    applySwellScheme(m, q);
    return q;
}

/// Numerical settings of the semi-implicit MPS solver (scene section "solver",
/// docs/scenes.md). The defaults are the swell scheme's, as a scene's without a scheme key;
/// schemeParams(Scheme::Textbook) gives the reference scheme.
struct SolverParams {
    Scheme scheme = Scheme::Swell; ///< the named set the settings started from
    TimeStepParams time;
    ModelParams model = swellModel();
    PressureParams pressure = swellPressure();
    NeighborParams neighbors;
};

/// The settings of a named scheme (everything else at its default).
inline SolverParams schemeParams(Scheme scheme) {
    SolverParams p;
    if (scheme == Scheme::Textbook) {
        p.scheme = Scheme::Textbook;
        p.model = ModelParams{};
        p.pressure = PressureParams{};
    }
    return p;
}

} // namespace swell::bake
