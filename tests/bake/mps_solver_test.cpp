#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include <Eigen/SparseCholesky>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>

#include "small_scenes.h"
#include "swell/bake/error.h"
#include "swell/bake/scene.h"

using namespace swell::bake;

// Allocation counter for the "no allocation in the step loop" test: replaces global
// operator new in this test binary only (not under AddressSanitizer, which owns it).
#if defined(__SANITIZE_ADDRESS__)
#define SWELL_COUNT_ALLOCATIONS 0
#else
#define SWELL_COUNT_ALLOCATIONS 1
#endif
namespace {
std::atomic<long> g_allocations{0};
}
#if SWELL_COUNT_ALLOCATIONS
void* operator new(std::size_t size) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size))
        return p;
    throw std::bad_alloc();
}
// Not inlined: GCC at -O1 would inline free() into `delete` after `new T` and warn of a
// mismatched pair (-Wmismatched-new-delete), not seeing that this `new` is malloc.
[[gnu::noinline]] void operator delete(void* p) noexcept {
    std::free(p);
}
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
#endif

namespace {

using swell::test::smallDamBreak;

/// Runs `steps` steps and returns the DivergenceError message, or "" if none.
std::string runUntilFailure(MpsSolver& solver, int steps) {
    try {
        for (int k = 0; k < steps; ++k)
            solver.step();
    } catch (const DivergenceError& e) {
        return e.what();
    }
    return "";
}

/// Particles whose position or velocity differs by any bit between two runs of one scene.
std::size_t particlesThatDiffer(const Particles& a, const Particles& b) {
    std::size_t d = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        d += a.x[i] != b.x[i] || a.y[i] != b.y[i] || a.vx[i] != b.vx[i] || a.vy[i] != b.vy[i];
    return d;
}

} // namespace

TEST(MpsSolver, PpeMatrixIsSymmetricDiagonallyDominantAndSolvedExactly) {
    for (Preconditioner pc : {Preconditioner::Jacobi, Preconditioner::SymmetricGaussSeidel,
                              Preconditioner::IncompleteCholesky, Preconditioner::TwoLevel}) {
        SCOPED_TRACE(std::string(toString(pc)));
        Scene scene = smallDamBreak();
        scene.solver.pressure.preconditioner = pc;
        scene.solver.pressure.tolerance = 1e-10;
        MpsSolver solver = makeSolver(scene);
        for (int k = 0; k < 30; ++k)
            solver.step();
        const Eigen::SparseMatrix<double, Eigen::RowMajor> A = solver.ppeMatrix();
        ASSERT_GT(A.rows(), 100);
        const Eigen::SparseMatrix<double, Eigen::RowMajor> At = A.transpose();
        EXPECT_LT((A - At).norm(), 1e-12 * A.norm());
        for (Eigen::Index r = 0; r < A.rows(); ++r) {
            double off = 0.0, diag = 0.0;
            for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, r); it; ++it) {
                if (it.col() == r)
                    diag = it.value();
                else {
                    EXPECT_LE(it.value(), 0.0);
                    off += std::abs(it.value());
                }
            }
            ASSERT_GT(diag, off) << "row " << r; // strictly dominant thanks to compressibility
        }
        // Our PCG result against a direct sparse Cholesky solve of the same system.
        const Eigen::SparseMatrix<double> Ac = A;
        Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> direct(Ac);
        ASSERT_EQ(direct.info(), Eigen::Success);
        const Eigen::VectorXd exact = direct.solve(solver.ppeRhs());
        const Eigen::VectorXd ours = solver.ppeSolution();
        EXPECT_LT((ours - exact).norm(), 1e-7 * exact.norm());
    }
}

// The thread count does not change a single bit of the state (numerics_version.h): a dam break
// of 9,600 water particles (well over the 4096 rows from which the pressure solve's
// matrix-vector product runs in parallel) stepped 60 times on 1 and on 3 threads (3 splits
// the rows unevenly).
TEST(MpsSolver, ResultsDoNotDependOnTheThreadCount) {
    Scene scene;
    scene.solver = schemeParams(Scheme::Textbook);
    scene.geometry.particleSpacing = 0.0025;
    scene.geometry.tank = Box{0.0, 0.0, 0.6, 0.3};
    scene.geometry.water = {Box{0.0, 0.0, 0.3, 0.2}};
    scene.solver.time.dt = 0.0002;
    const int before = omp_get_max_threads();
    const auto run = [&](int threads) {
        omp_set_num_threads(threads);
        MpsSolver solver = makeSolver(scene);
        for (int k = 0; k < 60; ++k)
            solver.step();
        omp_set_num_threads(before);
        return solver.exportState().particles;
    };
    const Particles one = run(1);
    const Particles three = run(3);
    ASSERT_GE(one.size(), std::size_t{9600});
    ASSERT_EQ(three.size(), one.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < one.size(); ++i) {
        differ += one.x[i] != three.x[i] || one.y[i] != three.y[i] || one.vx[i] != three.vx[i] ||
                  one.vy[i] != three.vy[i] || one.p[i] != three.p[i];
    }
    EXPECT_EQ(differ, 0u) << "particles whose state differs between 1 and 3 threads";
}

TEST(MpsSolver, PackingFactorIsOneOnTheStartLatticeAndOnlyActsWhenSet) {
    // re_packing unset: P = 1 and the default's bits. Set: P is 1 on the square lattice the
    // water starts on (to round-off) and moves once the dam break reorders the particles.
    Scene scene = smallDamBreak();
    scene.solver = schemeParams(Scheme::Swell);
    scene.solver.time.dt = 0.001;
    const auto run = [&](double rePacking, int steps, double* packing) {
        Scene s = scene;
        s.solver.model.rePacking = rePacking;
        MpsSolver solver = makeSolver(s);
        for (int k = 0; k < steps; ++k)
            solver.step();
        *packing = solver.packingFactor();
        return solver.exportState().particles;
    };
    double p0 = 0.0, p1 = 0.0, pOff = 0.0;
    (void)run(3.0, 1, &p1);
    EXPECT_NEAR(p1, 1.0, 1e-3) << "the start lattice, after one step";
    const Particles off = run(0.0, 80, &pOff);
    EXPECT_EQ(pOff, 1.0);
    const Particles on = run(3.0, 80, &p0);
    EXPECT_NE(p0, 1.0);
    EXPECT_GT(particlesThatDiffer(off, on), 0u);
}

namespace {
/// Steps `with` 40 times, gives `without` (other settings, same particles) the same state and
/// steps each once.
void stepBothFromTheSameState(MpsSolver& with, MpsSolver& without) {
    for (int k = 0; k < 40; ++k)
        with.step();
    without.importState(with.exportState());
    with.step();
    without.step();
}

/// stepBothFromTheSameState, and checks that the option under test left positions and
/// pressures alone.
void oneStepFromTheSameState(MpsSolver& with, MpsSolver& without) {
    stepBothFromTheSameState(with, without);
    EXPECT_EQ(with.particles().x, without.particles().x);
    EXPECT_EQ(with.particles().y, without.particles().y);
    EXPECT_EQ(with.particles().p, without.particles().p);
}

/// After oneStepFromTheSameState with the same surface flags: every particle whose velocity
/// differs between `slower` and `other` is a free-surface particle and is no faster in
/// `slower`. Returns how many differ.
std::size_t onlySurfaceParticlesSlowDown(const MpsSolver& slower, const MpsSolver& other) {
    const Particles& a = slower.particles();
    const Particles& b = other.particles();
    std::size_t changed = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a.vx[i] == b.vx[i] && a.vy[i] == b.vy[i])
            continue;
        ++changed;
        EXPECT_EQ(slower.surfaceFlags()[i], 1) << "particle " << i;
        EXPECT_LE(std::hypot(a.vx[i], a.vy[i]), std::hypot(b.vx[i], b.vy[i])) << "particle " << i;
    }
    return changed;
}
} // namespace

TEST(MpsSolver, ShiftDampingOnlyTakesSurfaceVelocityAgainstTheShift) {
    // solver.shift_damping: from the same dam-break state, one step with and one without it
    // put every particle in the same place with the same pressure; only free-surface
    // particles' velocities differ, and none of them is faster.
    Scene scene = smallDamBreak();
    scene.solver = schemeParams(Scheme::Swell);
    ASSERT_TRUE(scene.solver.model.shiftDamping);
    Scene plainScene = scene;
    plainScene.solver.model.shiftDamping = false;
    MpsSolver solver = makeSolver(scene);
    MpsSolver plainSolver = makeSolver(plainScene);
    oneStepFromTheSameState(solver, plainSolver);
    ASSERT_EQ(solver.surfaceFlags(), plainSolver.surfaceFlags());
    EXPECT_GT(onlySurfaceParticlesSlowDown(solver, plainSolver), 0u);
}

TEST(MpsSolver, ShiftDampingGainTakesMoreOfTheSameSurfaceVelocity) {
    // solver.shift_damping_gain: from the same dam-break state, one step at gain 2 and one at
    // gain 1 put every particle in the same place with the same pressure; only free-surface
    // particles' velocities differ, and none is faster at gain 2 (rho grows with the gain).
    Scene scene = smallDamBreak();
    scene.solver = schemeParams(Scheme::Swell);
    Scene unitScene = scene;
    ASSERT_EQ(unitScene.solver.model.shiftDampingGain, 1.0);
    scene.solver.model.shiftDampingGain = 2.0;
    MpsSolver solver = makeSolver(scene);
    MpsSolver unitSolver = makeSolver(unitScene);
    oneStepFromTheSameState(solver, unitSolver);
    ASSERT_EQ(solver.surfaceFlags(), unitSolver.surfaceFlags());
    EXPECT_GT(onlySurfaceParticlesSlowDown(solver, unitSolver), 0u);
}

TEST(MpsSolver, PreconditionersCutIterations) {
    int iterations[4] = {0, 0, 0, 0};
    int k = 0;
    for (Preconditioner pc : {Preconditioner::Jacobi, Preconditioner::SymmetricGaussSeidel,
                              Preconditioner::IncompleteCholesky, Preconditioner::TwoLevel}) {
        Scene scene = smallDamBreak();
        scene.solver.pressure.preconditioner = pc;
        MpsSolver solver = makeSolver(scene);
        for (int s = 0; s < 20; ++s)
            iterations[k] += solver.step().ppeIterations;
        ++k;
    }
    EXPECT_LT(iterations[1], iterations[0]);
    EXPECT_LT(iterations[2], iterations[1]);
    EXPECT_LT(iterations[3], iterations[0]); // the coarse solve removes smooth error modes
}

TEST(MpsSolver, StepReportsStatsAndPhaseTimes) {
    MpsSolver solver = makeSolver(smallDamBreak());
    const StepStats& s = solver.step();
    EXPECT_EQ(s.step, 1);
    EXPECT_DOUBLE_EQ(s.dt, 0.001);
    EXPECT_DOUBLE_EQ(solver.time(), 0.001);
    EXPECT_GT(s.ppeIterations, 0);
    EXPECT_LE(s.ppeResidual, solver.params().pressure.tolerance);
    EXPECT_GT(s.ppeUnknowns, 0u);
    EXPECT_GT(s.surfaceParticles, 0u);
    EXPECT_EQ(s.outOfBounds, 0u);
    EXPECT_NEAR(s.courant, s.maxSpeed * s.dt / 0.01, 1e-12);
    for (double t : s.phaseSeconds)
        EXPECT_GE(t, 0.0);
    EXPECT_GT(s.seconds(), 0.0);
}

TEST(MpsSolver, WaterAtRestOnALatticeWithoutGravityStaysAtRest) {
    Scene scene = smallDamBreak();
    scene.physics.gravity = 0.0;
    MpsSolver solver = makeSolver(scene);
    const Particles before = solver.particles();
    for (int k = 0; k < 50; ++k)
        solver.step();
    const Particles& after = solver.particles();
    for (std::size_t i = 0; i < after.size(); ++i) {
        ASSERT_NEAR(after.x[i], before.x[i], 1e-9);
        ASSERT_NEAR(after.y[i], before.y[i], 1e-9);
    }
}

TEST(MpsSolver, AdaptiveStepKeepsTheCourantTarget) {
    Scene scene = smallDamBreak();
    scene.solver.time.dt = 0.004;
    scene.solver.time.adaptive = true;
    scene.solver.time.courantTarget = 0.2;
    MpsSolver solver = makeSolver(scene);
    double smallest = 1.0;
    for (int k = 0; k < 150; ++k) {
        const StepStats& s = solver.step();
        smallest = std::min(smallest, s.dt);
        ASSERT_LE(s.dt, 0.004);
    }
    EXPECT_LT(smallest, 0.004); // the column collapses fast enough to need smaller steps
}

TEST(MpsSolver, StepLoopDoesNotAllocate) {
    if (!SWELL_COUNT_ALLOCATIONS)
        GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
    MpsSolver solver = makeSolver(smallDamBreak());
    for (int k = 0; k < 20; ++k)
        solver.step(); // warm-up (OpenMP thread pool, first rebuilds)
    const long before = g_allocations.load();
    int rebuilds = 0;
    for (int k = 0; k < 100; ++k)
        rebuilds += solver.step().neighborRebuilds;
    EXPECT_EQ(g_allocations.load() - before, 0);
    EXPECT_GT(rebuilds, 0); // the rebuild path was exercised too
}

TEST(MpsSolver, DetectorStopsOnCourantNumberAboveTheLimit) {
    Scene scene = smallDamBreak();
    scene.solver.time.dt = 0.006;           // far above what the collapse allows ...
    scene.solver.time.substepCourant = 0.0; // ... when no step is split
    MpsSolver solver = makeSolver(scene);
    const std::string msg = runUntilFailure(solver, 200);
    ASSERT_FALSE(msg.empty()) << "a too-large step must be stopped";
    EXPECT_NE(msg.find("step"), std::string::npos);
    EXPECT_NE(msg.find("particle"), std::string::npos);
    EXPECT_NE(msg.find("courant_limit"), std::string::npos) << msg;
    EXPECT_NE(msg.find("a smaller solver.dt, or solver.substep_courant > 0"), std::string::npos)
        << msg;
}

// The detector's message says what to change: with the limit lowered to the sub-step
// threshold (the default until 2026-12-02), sub-steps never act, so it points at the limit.
TEST(MpsSolver, DetectorSaysHowSubstepsCouldFollowTheFlow) {
    Scene scene = smallDamBreak();
    scene.solver.time.dt = 0.006;
    scene.solver.time.courantLimit = scene.solver.time.substepCourant;
    MpsSolver solver = makeSolver(scene);
    const std::string msg = runUntilFailure(solver, 200);
    ASSERT_FALSE(msg.empty()) << "a too-large step must be stopped";
    EXPECT_NE(msg.find("raise solver.courant_limit"), std::string::npos) << msg;
    EXPECT_NE(msg.find("solver.substep_courant 0.5"), std::string::npos) << msg;
}

// Sub-steps (TimeStepParams::substepCourant): with the default limits (sub-steps from 0.5,
// the detector at 0.8), the same too-large step is split as soon as the previous step's
// fastest particle would cross more than 0.5 l0, so the collapse runs 0.6 s (100 steps)
// without reaching the limit; each step still advances exactly dt, and the number of
// sub-steps follows the speed, ceil(max|u| dt / (0.5 l0)). No scene key is needed for it.
TEST(MpsSolver, SubstepsFollowAFlowTheStepIsTooLongFor) {
    Scene scene = smallDamBreak();
    scene.solver.time.dt = 0.006;
    ASSERT_GT(scene.solver.time.courantLimit, scene.solver.time.substepCourant);
    MpsSolver solver = makeSolver(scene);
    int most = 1;
    for (int k = 0; k < 100; ++k) {
        const double before = solver.time();
        const double speed = solver.exportState().lastMaxSpeed;
        const StepStats& s = solver.step();
        const double courant = speed * 0.006 / 0.01;
        EXPECT_EQ(s.substeps, courant > 0.5 ? static_cast<int>(std::ceil(courant / 0.5)) : 1)
            << "step " << s.step;
        EXPECT_LE(s.courant, scene.solver.time.courantLimit);
        EXPECT_EQ(solver.time(), before + 0.006) << "step " << s.step;
        most = std::max(most, s.substeps);
    }
    EXPECT_GE(most, 3) << "the collapse reaches 3 x 0.5 l0 per step of 6 ms";
    scene.solver.time.substepCourant = 0.0;
    MpsSolver whole = makeSolver(scene);
    EXPECT_NE(runUntilFailure(whole, 100), "") << "without sub-steps the detector stops it";
}

// A flow too fast even for kMaxSubsteps sub-steps is still stopped, and the message says in
// which sub-step.
TEST(MpsSolver, DetectorNamesTheSubstepItStopsIn) {
    const Scene scene = smallDamBreak();
    MpsSolver solver = makeSolver(scene);
    solver.step();
    MpsState state = solver.exportState();
    state.particles.vx[5] = 2000.0; // 200 l0 per step: 400 sub-steps would be needed
    state.lastMaxSpeed = 2000.0;
    solver.importState(state);
    const std::string msg = runUntilFailure(solver, 1);
    EXPECT_NE(msg.find("in sub-step 1 of 64"), std::string::npos) << msg;
    EXPECT_NE(msg.find("step 2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("faster than the sub-steps follow"), std::string::npos) << msg;
}

TEST(MpsSolver, DetectorNamesStepTimeAndParticleForNonFiniteState) {
    GeneratedGeometry g = generateGeometry(smallDamBreak().geometry);
    g.particles.vx[17] = std::numeric_limits<double>::quiet_NaN();
    MpsSolver solver(PhysicsParams{}, smallDamBreak().solver, g.particles, 0.01, g.domain);
    try {
        solver.step();
        FAIL() << "NaN velocity not detected";
    } catch (const DivergenceError& e) {
        EXPECT_EQ(e.step(), 1);
        EXPECT_NEAR(e.time(), 0.001, 1e-12);
        // The NaN spreads to neighbours through viscosity within the step; the detector
        // names the lowest-index non-finite particle: 17 or one of its neighbours.
        const Particles& P = g.particles;
        const std::size_t named = e.particle();
        EXPECT_LT(std::hypot(P.x[named] - P.x[17], P.y[named] - P.y[17]), 3.6 * 0.01) << e.what();
        EXPECT_NE(std::string(e.what()).find(fmt::format("particle {}", named)), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
    }
}

TEST(MpsSolver, DetectorStopsWhenAParticleLeavesTheDomain) {
    const Scene scene = smallDamBreak();
    GeneratedGeometry g = generateGeometry(scene.geometry);
    g.particles.vx[5] = 400.0; // 0.4 m per step: out of the domain at once
    SolverParams par = scene.solver;
    par.time.courantLimit = 1e9; // so the domain check is the one that fires
    MpsSolver solver(PhysicsParams{}, par, g.particles, 0.01, g.domain);
    const std::string msg = runUntilFailure(solver, 3);
    ASSERT_FALSE(msg.empty());
    EXPECT_NE(msg.find("particle 5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("domain"), std::string::npos) << msg;
    EXPECT_NE(msg.find("right of it"), std::string::npos) << msg;

    // Spray that flies out through the top is named as such, with what to change.
    GeneratedGeometry up = generateGeometry(scene.geometry);
    up.particles.vy[5] = 400.0;
    MpsSolver high(PhysicsParams{}, par, up.particles, 0.01, up.domain);
    const std::string top = runUntilFailure(high, 3);
    EXPECT_NE(top.find("above its top"), std::string::npos) << top;
    EXPECT_NE(top.find("geometry.domain"), std::string::npos) << top;
}

TEST(MpsSolver, DetectorStopsOnAnUnconvergedPressureSolve) {
    Scene scene = smallDamBreak();
    scene.solver.pressure.maxIterations = 2;
    scene.solver.pressure.tolerance = 1e-12;
    MpsSolver solver = makeSolver(scene);
    const std::string msg = runUntilFailure(solver, 5);
    EXPECT_NE(msg.find("did not converge"), std::string::npos) << msg;
}

TEST(MpsSolver, RejectsUnusableConstruction) {
    const GeneratedGeometry g = generateGeometry(smallDamBreak().geometry);
    SolverParams bad;
    bad.time.dt = 0.0;
    EXPECT_THROW(MpsSolver(PhysicsParams{}, bad, g.particles, 0.01, g.domain),
                 std::invalid_argument);
    EXPECT_THROW(
        MpsSolver(PhysicsParams{}, SolverParams{}, g.particles, 0.01, Box{0, 0, 0.01, 0.01}),
        std::invalid_argument);
    Particles walls;
    walls.add(0.0, 0.0, ParticleKind::Wall);
    EXPECT_THROW(MpsSolver(PhysicsParams{}, SolverParams{}, walls, 0.01, g.domain),
                 std::invalid_argument);
}

TEST(MpsSolver, TwoSolversInOneProcessAreIndependent) {
    MpsSolver a = makeSolver(smallDamBreak());
    MpsSolver b = makeSolver(smallDamBreak());
    for (int k = 0; k < 10; ++k)
        a.step();
    b.step();
    EXPECT_EQ(a.stepCount(), 10);
    EXPECT_EQ(b.stepCount(), 1);
    MpsSolver c = makeSolver(smallDamBreak());
    for (int k = 0; k < 9; ++k)
        b.step();
    for (int k = 0; k < 10; ++k)
        c.step();
    for (std::size_t i = 0; i < a.particles().size(); ++i) {
        ASSERT_NEAR(a.particles().x[i], b.particles().x[i], 1e-8);
        ASSERT_NEAR(c.particles().y[i], b.particles().y[i], 1e-8);
    }
}

// Paper Sec. 3.3.1: the piston (the tank's back wall) follows its prescribed motion exactly,
// rigidly, and pushes the water; the bed does not move.
TEST(MpsSolver, PistonBackWallFollowsItsMotionAndPushesWater) {
    Scene scene;
    scene.solver = schemeParams(Scheme::Textbook);
    scene.geometry.particleSpacing = 0.02;
    scene.geometry.tank = Box{0.0, 0.0, 0.8, 0.3};
    scene.geometry.water = {Box{0.0, 0.0, 0.8, 0.12}};
    scene.solver.time.dt = 0.002;
    scene.run.endTime = 0.25;
    PistonParams piston;
    piston.kind = PistonKind::Sinusoidal;
    piston.period = 1.0;
    piston.stroke = 0.06;
    piston.rampTime = 0.0;
    scene.piston = piston;
    scene.geometry.bedExtensionBack = 0.03; // parseScene's S/2
    MpsSolver solver = makeSolver(scene);
    const GeneratedGeometry geo = generateGeometry(scene.geometry);
    ASSERT_EQ(geo.backWall.size(), 4u * 15u); // 2 wall + 2 dummy layers, 0.3 m / 0.02 m rows
    const PistonMotion motion(*scene.piston, scene.run.endTime);
    const Particles& P = solver.particles();
    double meanU = 0.0;
    for (int k = 0; k < 125; ++k)
        solver.step(); // a quarter period: the piston moves forward
    const PistonState s = motion.at(solver.time());
    ASSERT_GT(s.displacement, 0.02);
    std::vector<std::uint8_t> isBack(P.size(), 0);
    for (std::uint32_t i : geo.backWall) {
        isBack[i] = 1;
        EXPECT_NEAR(P.x[i], geo.particles.x[i] + s.displacement, 1e-12);
        EXPECT_DOUBLE_EQ(P.y[i], geo.particles.y[i]);
        EXPECT_NEAR(P.vx[i], s.velocity, 1e-12);
    }
    std::size_t nearPiston = 0;
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] != ParticleKind::Water) {
            if (!isBack[i]) {
                EXPECT_EQ(P.x[i], geo.particles.x[i]) << "fixed particle " << i << " moved";
            }
            continue;
        }
        EXPECT_GT(P.x[i], s.displacement) << "water particle " << i << " behind the piston face";
        if (geo.particles.x[i] < 0.1) {
            meanU += P.x[i] - geo.particles.x[i];
            ++nearPiston;
        }
    }
    EXPECT_GT(meanU / static_cast<double>(nearPiston), 0.5 * s.displacement); // pushed along
}

// A block whose spacing is 3 % wider than l0 has n* < beta n0 everywhere. The density test
// (paper eq. (3)) then calls every particle free surface; the distribution test keeps the
// interior in the pressure solve and flags only the one-sided outer layer.
TEST(MpsSolver, DistributionSurfaceTestKeepsAnExpandedInteriorInThePressureSolve) {
    const double l0 = 0.01, spread = 1.03 * l0;
    Particles P;
    for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i)
            P.add(0.1 + spread * i, 0.1 + spread * j, ParticleKind::Water);
    const Box domain{0.0, 0.0, 0.4, 0.4};
    auto surfaceCount = [&](SurfaceTest test, std::size_t& interior) {
        SolverParams par = schemeParams(Scheme::Textbook); // no shifting
        par.model.surfaceTest = test;
        PhysicsParams phys;
        phys.gravity = 0.0;
        MpsSolver solver(phys, par, P, l0, domain);
        solver.step();
        std::size_t count = 0;
        interior = 0;
        const Particles& q = solver.particles();
        for (std::size_t k = 0; k < q.size(); ++k) {
            count += solver.surfaceFlags()[k] == 1;
            const bool inner = q.x[k] > 0.1 + 2.5 * spread && q.x[k] < 0.1 + 8.5 * spread &&
                               q.y[k] > 0.1 + 2.5 * spread && q.y[k] < 0.1 + 8.5 * spread;
            interior += inner && solver.surfaceFlags()[k] == 1;
        }
        return count;
    };
    std::size_t interior = 0;
    EXPECT_EQ(surfaceCount(SurfaceTest::Density, interior), P.size());
    EXPECT_GT(interior, 0u);
    const std::size_t flagged = surfaceCount(SurfaceTest::Distribution, interior);
    EXPECT_EQ(interior, 0u);
    EXPECT_GE(flagged, 44u); // at least the outer ring of 4 x 11
    EXPECT_LT(flagged, P.size() / 2);
}
