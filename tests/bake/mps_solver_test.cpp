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

TEST(MpsSolver, DensityRelaxationTakesItsOwnKernelOnlyWhereItDiffers) {
    // re_relaxation at re_density is the one-kernel code bit for bit (its sum then reuses n*);
    // another radius changes the pressure source, hence the flow.
    Scene scene = smallDamBreak();
    scene.solver = schemeParams(Scheme::Swell);
    scene.solver.time.dt = 0.001;
    const auto run = [&](double reRelaxation) {
        Scene s = scene;
        s.solver.model.reRelaxation = reRelaxation;
        MpsSolver solver = makeSolver(s);
        for (int k = 0; k < 40; ++k)
            solver.step();
        return solver.exportState().particles;
    };
    const Particles unset = run(0.0);
    EXPECT_EQ(particlesThatDiffer(unset, run(scene.solver.model.reDensity)), 0u);
    EXPECT_EQ(particlesThatDiffer(unset, run(3.0)),
              unset.count(ParticleKind::Water)); // every water particle
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

TEST(MpsSolver, RelaxationAndShiftingArePerReferenceStep) {
    // With reference_step = 1 ms, gamma and C are given per millisecond: a 2 ms step applies
    // twice each, exactly what per-step coefficients (reference_step 0, the default) of twice
    // the value do. So the relaxation and the shifting act at one rate per second whatever
    // the step.
    Scene scene = smallDamBreak();
    scene.solver = schemeParams(Scheme::Swell);
    EXPECT_EQ(scene.solver.time.referenceStep, 0.0); // the default: per step
    scene.solver.time.dt = 0.002;
    const auto run = [&](double referenceStep, double gamma, double shifting) {
        Scene s = scene;
        s.solver.time.referenceStep = referenceStep;
        s.solver.pressure.relaxation = gamma;
        s.solver.model.shifting = shifting;
        MpsSolver solver = makeSolver(s);
        for (int k = 0; k < 60; ++k)
            solver.step();
        return solver.exportState().particles;
    };
    const Particles scaled = run(0.001, 0.02, 0.02);
    EXPECT_EQ(particlesThatDiffer(scaled, run(0.0, 0.04, 0.04)), 0u);
    // The step equal to reference_step: the per-step bits.
    EXPECT_EQ(particlesThatDiffer(run(0.002, 0.02, 0.02), run(0.0, 0.02, 0.02)), 0u);
    // And the scale acts on both: doubling only one of them is another result.
    EXPECT_GT(particlesThatDiffer(scaled, run(0.0, 0.04, 0.02)), 0u);
    EXPECT_GT(particlesThatDiffer(scaled, run(0.0, 0.02, 0.04)), 0u);
    TimeStepParams perMillisecond;
    perMillisecond.referenceStep = 0.001;
    EXPECT_DOUBLE_EQ(coefficientScale(perMillisecond, 0.0005), 0.5);
    EXPECT_EQ(coefficientScale(TimeStepParams{}, 0.0005), 1.0); // per step
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

/// A solver for `scene` that takes one step from `state`.
MpsSolver stepOnceFrom(const Scene& scene, const MpsState& state) {
    MpsSolver solver = makeSolver(scene);
    solver.importState(state);
    solver.step();
    return solver;
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

TEST(MpsSolver, ShiftingVelocityFollowsTheShiftWithTheVelocityGradient) {
    // solver.shifting_velocity: u += (dr . grad) u after the shift. A block of water moving
    // uniformly without gravity keeps its lattice, its zero pressures and so a uniform
    // velocity, while its surface particles are shifted along the surface: the gradient of a
    // uniform field is zero, so the correction changes no bit.
    SolverParams params = schemeParams(Scheme::Swell);
    ASSERT_GT(params.model.shifting, 0.0);
    params.model.shiftDamping = false; // it would slow the shifted surface particles
    PhysicsParams still;
    still.gravity = 0.0;
    const double l0 = 0.01;
    Particles block;
    for (int j = 0; j < 10; ++j) {
        for (int i = 0; i < 20; ++i)
            block.add((i + 0.5) * l0, (j + 0.5) * l0, ParticleKind::Water);
    }
    std::fill(block.vx.begin(), block.vx.end(), 0.2);
    std::fill(block.vy.begin(), block.vy.end(), 0.1);
    const Box domain{-1.0, -1.0, 1.0, 1.0};
    const auto uniform = [&](bool follow) {
        SolverParams p = params;
        p.model.shiftingVelocity = follow;
        MpsSolver solver(still, p, block, l0, domain);
        for (int k = 0; k < 20; ++k)
            solver.step();
        return solver.exportState().particles;
    };
    const Particles kept = uniform(false);
    EXPECT_EQ(particlesThatDiffer(kept, uniform(true)), 0u);
    // The block moved, and the shifting moved its surface particles off the rigid motion.
    std::size_t shifted = 0;
    const double travel = 20 * params.time.dt;
    for (std::size_t i = 0; i < kept.size(); ++i) {
        EXPECT_EQ(kept.vx[i], 0.2);
        shifted += std::hypot(kept.x[i] - block.x[i] - 0.2 * travel,
                              kept.y[i] - block.y[i] - 0.1 * travel) > 1e-3 * l0;
    }
    EXPECT_GT(shifted, 0u);

    // In a dam break the velocity varies: the correction changes the velocities of the
    // shifted particles and, within the step, nothing else.
    Scene scene = smallDamBreak();
    scene.solver = params;
    Scene follow = scene;
    follow.solver.model.shiftingVelocity = true;
    MpsSolver solver = makeSolver(follow);
    MpsSolver plainSolver = makeSolver(scene);
    oneStepFromTheSameState(solver, plainSolver);
    const Particles& corrected = solver.particles();
    const Particles& plain = plainSolver.particles();
    EXPECT_GT(particlesThatDiffer(corrected, plain), 100u) << "velocities follow the shift";
}

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

TEST(MpsSolver, ShiftDeadBandTakesItsWidthFromEachInteriorShiftAndLeavesTheSurfaceAlone) {
    // solver.shift_dead_band b: from the same dam-break state, one step with b = 0.001 l0 and
    // one without put every free-surface particle in the same place (their shift along the
    // surface is left alone), and move each interior water particle by its shift less b, or
    // not at all where the shift is shorter: the two places differ by min(|s|, b), never more
    // than b, and exactly b for a particle whose shift was longer.
    Scene scene = smallDamBreak();
    scene.solver = schemeParams(Scheme::Swell);
    ASSERT_EQ(scene.solver.model.shiftDeadBand, 0.0);
    ASSERT_GT(scene.solver.model.shifting, 0.0);
    Scene banded = scene;
    const double b = 0.001;
    banded.solver.model.shiftDeadBand = b;
    MpsSolver with = makeSolver(banded);
    MpsSolver without = makeSolver(scene);
    stepBothFromTheSameState(with, without);
    ASSERT_EQ(with.surfaceFlags(), without.surfaceFlags());
    const Particles& a = with.particles();
    const Particles& c = without.particles();
    const double l0 = scene.geometry.particleSpacing;
    std::size_t interior = 0, fullBand = 0, held = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a.kind[i] != ParticleKind::Water)
            continue;
        const double d = std::hypot(a.x[i] - c.x[i], a.y[i] - c.y[i]) / l0;
        if (with.surfaceFlags()[i] == 1) {
            EXPECT_EQ(a.x[i], c.x[i]) << "surface particle " << i;
            EXPECT_EQ(a.y[i], c.y[i]) << "surface particle " << i;
            continue;
        }
        ++interior;
        EXPECT_LE(d, b + 1e-9) << "particle " << i;
        if (std::abs(d - b) < 1e-9)
            ++fullBand;
        else
            ++held; // a shift shorter than the band: not moved at all
    }
    EXPECT_GT(interior, 100u);
    EXPECT_GT(fullBand, 0u); // some shifts are longer than the band, some shorter
    EXPECT_GT(held, 0u);
}

TEST(MpsSolver, ShiftClosePairsPushesApartOnlyAPairCloserThanTheSpacing) {
    // solver.shift_close_pairs: water at rest on its start lattice without gravity, one
    // interior particle moved 0.3 l0 towards its right-hand neighbour. The shift comes last in a
    // step, so against a step without shifting (the same r*, pressures and velocities) the
    // close-pairs step moves that pair alone, apart along the line between them by the same
    // amount: every other pair is l0 or more apart. The default's shift, summed over the density
    // kernel, moves many particles around it.
    Scene scene = smallDamBreak();
    scene.physics.gravity = 0.0;
    scene.solver = schemeParams(Scheme::Swell);
    ASSERT_EQ(scene.solver.model.shiftClosePairs, 0.0);
    Scene none = scene;
    none.solver.model.shifting = 0.0;
    none.solver.model.shiftDamping = false;
    Scene close = scene;
    close.solver.model.shiftClosePairs = 2.0;
    const double l0 = scene.geometry.particleSpacing;

    MpsState state = makeSolver(scene).exportState();
    Particles& start = state.particles;
    const auto nearestWater = [&](double x, double y) {
        std::size_t best = start.size();
        double bestD = 1e9;
        for (std::size_t i = 0; i < start.size(); ++i) {
            const double d = std::hypot(start.x[i] - x, start.y[i] - y);
            if (start.kind[i] == ParticleKind::Water && d < bestD) {
                bestD = d;
                best = i;
            }
        }
        return best;
    };
    const std::size_t k = nearestWater(0.05, 0.1);
    const std::size_t right = nearestWater(start.x[k] + l0, start.y[k]);
    ASSERT_NEAR(start.x[right] - start.x[k], l0, 1e-12);
    start.x[k] += 0.3 * l0;

    const auto stepFrom = [&](const Scene& s) {
        const MpsSolver solver = stepOnceFrom(s, state);
        EXPECT_EQ(solver.surfaceFlags()[k], 0);
        return solver.particles();
    };
    const Particles a = stepFrom(close);
    const Particles b = stepFrom(none);
    const Particles c = stepFrom(scene);
    ASSERT_EQ(a.p, b.p);
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (i == k || i == right)
            continue;
        EXPECT_EQ(a.x[i], b.x[i]) << "particle " << i;
        EXPECT_EQ(a.y[i], b.y[i]) << "particle " << i;
    }
    const double pushK = a.x[k] - b.x[k], pushRight = a.x[right] - b.x[right];
    EXPECT_LT(pushK, -1e-6 * l0); // apart: k to the left, its neighbour to the right
    EXPECT_NEAR(pushRight, -pushK, 1e-12 * l0);
    EXPECT_EQ(a.y[k], b.y[k]);
    EXPECT_EQ(a.y[right], b.y[right]);
    EXPECT_GT(particlesThatDiffer(c, b), 10u);
}

TEST(MpsSolver, ShiftClosePairsInTheBulkLeavesTheSurfaceAndTheWallsToTheDefaultsShift) {
    // solver.shift_close_pairs_region "bulk": from the same dam-break state (40 steps in), one
    // step each with the default's shift, with close pairs everywhere and with close pairs in
    // the bulk. The shift comes last and moves each particle by its own sums, so every water
    // particle of the bulk step lands exactly where one of the other two put it: where close
    // pairs put it in the bulk, where the default put it on the free surface and next to a wall
    // (a wall or dummy particle on the density kernel; 2.5 l0 at the step's start leaves room
    // for the step's motion). Both kinds occur.
    Scene scene = smallDamBreak();
    scene.solver = schemeParams(Scheme::Swell);
    ASSERT_EQ(scene.solver.model.shiftClosePairsRegion, ClosePairsRegion::Everywhere);
    Scene everywhere = scene;
    everywhere.solver.model.shiftClosePairs = 2.0;
    Scene bulk = everywhere;
    bulk.solver.model.shiftClosePairsRegion = ClosePairsRegion::Bulk;
    MpsSolver start = makeSolver(scene);
    for (int k = 0; k < 40; ++k)
        start.step();
    const MpsState state = start.exportState();
    const MpsSolver b = stepOnceFrom(bulk, state);
    const Particles& inBulk = b.particles();
    const Particles closeEverywhere = stepOnceFrom(everywhere, state).particles();
    const Particles byDefault = stepOnceFrom(scene, state).particles();
    ASSERT_EQ(inBulk.p, byDefault.p);
    const Particles& at = state.particles;
    const double l0 = scene.geometry.particleSpacing;
    const auto nearBoundary = [&](std::size_t i) {
        for (std::size_t j = 0; j < at.size(); ++j) {
            if (at.kind[j] != ParticleKind::Water &&
                std::hypot(at.x[j] - at.x[i], at.y[j] - at.y[i]) < 2.5 * l0)
                return true;
        }
        return false;
    };
    std::size_t asClosePairs = 0, asDefault = 0;
    for (std::size_t i = 0; i < inBulk.size(); ++i) {
        if (inBulk.kind[i] != ParticleKind::Water)
            continue;
        const bool same =
            closeEverywhere.x[i] == byDefault.x[i] && closeEverywhere.y[i] == byDefault.y[i];
        const bool close =
            inBulk.x[i] == closeEverywhere.x[i] && inBulk.y[i] == closeEverywhere.y[i];
        const bool plain = inBulk.x[i] == byDefault.x[i] && inBulk.y[i] == byDefault.y[i];
        EXPECT_TRUE(close || plain) << "particle " << i;
        if (same)
            continue;
        asClosePairs += close;
        asDefault += plain;
        if (b.surfaceFlags()[i] == 1 || nearBoundary(i)) {
            EXPECT_TRUE(plain) << "particle " << i;
        }
    }
    EXPECT_GT(asClosePairs, 20u);
    EXPECT_GT(asDefault, 20u);
}

TEST(MpsSolver, ShiftDampingWallGainActsOnlyNextToTheWalls) {
    // solver.shift_damping_wall_gain: from the same dam-break state, one step at wall gain 2
    // and one at the default (1, the open surface's gain) put every particle in the same place with
    // the same pressure; only the velocities of free-surface particles with a wall particle within
    // kWallReach l0 differ (the column's top at the left wall, the surge front on the bed),
    // none is faster at 2, and the open surface (the column's top away from the walls, the
    // collapsing face) keeps the same bits.
    Scene scene = smallDamBreak();
    scene.solver = schemeParams(Scheme::Swell);
    Scene defaultScene = scene;
    ASSERT_EQ(defaultScene.solver.model.shiftDampingWallGain, 1.0);
    ASSERT_EQ(defaultScene.solver.model.shiftDampingGain, 1.0);
    scene.solver.model.shiftDampingWallGain = 2.0;
    MpsSolver solver = makeSolver(scene);
    MpsSolver defaultSolver = makeSolver(defaultScene);
    oneStepFromTheSameState(solver, defaultSolver);
    ASSERT_EQ(solver.surfaceFlags(), defaultSolver.surfaceFlags());
    EXPECT_GT(onlySurfaceParticlesSlowDown(solver, defaultSolver), 0u);
    const Particles& a = solver.particles();
    const Particles& b = defaultSolver.particles();
    const double l0 = scene.geometry.particleSpacing;
    // The distance to the nearest wall particle after the step; the test read it at r*,
    // within the step's motion (far below 0.5 l0 here) of these positions.
    auto wallDistance = [&](std::size_t i) {
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < a.size(); ++j) {
            if (a.kind[j] == ParticleKind::Wall)
                best = std::min(best, std::hypot(a.x[j] - a.x[i], a.y[j] - a.y[i]));
        }
        return best;
    };
    std::size_t openSurface = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a.kind[i] != ParticleKind::Water || solver.surfaceFlags()[i] != 1)
            continue;
        const double d = wallDistance(i);
        if (a.vx[i] != b.vx[i] || a.vy[i] != b.vy[i]) {
            EXPECT_LT(d, (kWallReach + 0.5) * l0) << "particle " << i;
        }
        if (d > (kWallReach + 0.5) * l0)
            ++openSurface;
    }
    EXPECT_GT(openSurface, 10u) << "the scene must have open surface to leave alone";
}

TEST(MpsSolver, TruncatedDensityRaisesThePressureUnderTheSurface) {
    // solver.truncated_density: the rows a free surface truncates aim at n0 P (1 - k |f|),
    // below n0 P, so from the same state the density term no longer asks them to pull their
    // neighbours in towards a density they cannot reach: the water's pressures read higher on
    // average.
    Scene scene = smallDamBreak();
    scene.solver = schemeParams(Scheme::Swell);
    Scene offScene = scene;
    ASSERT_EQ(offScene.solver.model.truncatedDensity, 0.0);
    scene.solver.model.truncatedDensity = 0.5;
    MpsSolver solver = makeSolver(scene);
    MpsSolver offSolver = makeSolver(offScene);
    stepBothFromTheSameState(solver, offSolver);
    const Particles& on = solver.particles();
    const Particles& off = offSolver.particles();
    double sumOn = 0.0, sumOff = 0.0;
    for (std::size_t i = 0; i < on.size(); ++i) {
        if (on.kind[i] != ParticleKind::Water)
            continue;
        sumOn += on.p[i];
        sumOff += off.p[i];
    }
    EXPECT_GT(sumOn, sumOff);
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
        SolverParams par;
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
