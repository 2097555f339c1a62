// The pressure Poisson solve on its own (pressure_solver.h): a small SPD system, solved
// densely with Eigen for reference; every preconditioner converges to the same answer.
#include "swell/bake/pressure_solver.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

using namespace swell::bake;

namespace {

constexpr int kNx = 12, kNy = 9; // unknowns on a kNx x kNy lattice
constexpr int kCellSide = 3;     // 3 x 3 unknowns per grid cell (two-level aggregates)
constexpr std::size_t kRoom = 7; // room per row: 5 entries used at most, gaps left

/// The 5-point Laplacian with a diagonal shift (SPD, like the PPE with its artificial
/// compressibility) in `s`'s storage, with b_i = sin-like values; returns the dense copy.
Eigen::MatrixXd fillSystem(PressureSolver& s) {
    const int n = kNx * kNy;
    SparseRows& A = s.matrix();
    A.rows = static_cast<std::size_t>(n);
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
    const auto id = [](int x, int y) { return y * kNx + x; };
    for (int r = 0; r < n; ++r) {
        const int x = r % kNx, y = r / kNx;
        const auto ur = static_cast<std::size_t>(r);
        A.rowPtr[ur] = static_cast<int>(ur * kRoom);
        int pos = A.rowPtr[ur];
        const auto put = [&](int c, double v) {
            A.col[static_cast<std::size_t>(pos)] = c;
            A.val[static_cast<std::size_t>(pos)] = v;
            dense(r, c) = v;
            ++pos;
        };
        if (y > 0)
            put(id(x, y - 1), -1.0);
        if (x > 0)
            put(id(x - 1, y), -1.0);
        A.diagPos[ur] = pos;
        put(r, 4.05);
        if (x + 1 < kNx)
            put(id(x + 1, y), -1.0);
        if (y + 1 < kNy)
            put(id(x, y + 1), -1.0);
        A.rowNnz[ur] = pos - A.rowPtr[ur];
        s.rowCells()[ur] =
            static_cast<std::uint32_t>((y / kCellSide) * (kNx / kCellSide) + x / kCellSide);
        s.rhs()[ur] = std::sin(0.3 * r) + 0.5;
        s.solution()[ur] = 0.0;
    }
    A.rowPtr[static_cast<std::size_t>(n)] = static_cast<int>(static_cast<std::size_t>(n) * kRoom);
    return dense;
}

PressureSolver makeSolver(Preconditioner p, double tolerance = 1e-10, int iterations = 500) {
    return PressureSolver(p, tolerance, iterations, kNx * kNy, kRoom, kNx / kCellSide,
                          kNy / kCellSide);
}

Eigen::VectorXd asVector(const std::vector<double>& v, int n) {
    return Eigen::Map<const Eigen::VectorXd>(v.data(), n);
}

constexpr Preconditioner kAll[] = {Preconditioner::Jacobi, Preconditioner::SymmetricGaussSeidel,
                                   Preconditioner::IncompleteCholesky, Preconditioner::TwoLevel};

} // namespace

TEST(PressureSolver, MultiplyMatchesTheDenseMatrix) {
    PressureSolver s = makeSolver(Preconditioner::Jacobi);
    const Eigen::MatrixXd dense = fillSystem(s);
    const int n = kNx * kNy;
    std::vector<double> v(static_cast<std::size_t>(n)), out(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
        v[static_cast<std::size_t>(i)] = std::cos(0.7 * i);
    const double vAv = s.matrix().multiply(v.data(), out.data());
    const Eigen::VectorXd ref = dense * asVector(v, n);
    EXPECT_LT((asVector(out, n) - ref).norm(), 1e-12 * ref.norm());
    EXPECT_NEAR(vAv, asVector(v, n).dot(ref), 1e-10 * std::abs(vAv));
}

TEST(PressureSolver, EveryPreconditionerConvergesToTheDenseSolution) {
    const int n = kNx * kNy;
    for (Preconditioner p : kAll) {
        SCOPED_TRACE(std::string(toString(p)));
        PressureSolver s = makeSolver(p);
        const Eigen::MatrixXd dense = fillSystem(s);
        const Eigen::VectorXd b = asVector(s.rhs(), n);
        const Eigen::VectorXd exact = dense.llt().solve(b);
        const PressureSolveResult res = s.solve();
        EXPECT_EQ(res.status, PressureSolveStatus::Converged);
        EXPECT_GT(res.iterations, 0);
        EXPECT_LE(res.relativeResidual, 1e-10);
        const Eigen::VectorXd x = asVector(s.solution(), n);
        EXPECT_LT((dense * x - b).norm(), 1e-9 * b.norm());
        EXPECT_LT((x - exact).norm(), 1e-8 * exact.norm());
    }
}

TEST(PressureSolver, StrongerPreconditionersNeedFewerIterations) {
    int iterations[4] = {};
    for (int k = 0; k < 4; ++k) {
        PressureSolver s = makeSolver(kAll[k]);
        fillSystem(s);
        iterations[k] = s.solve().iterations;
    }
    EXPECT_LT(iterations[1], iterations[0]); // Gauss-Seidel beats Jacobi
    EXPECT_LT(iterations[2], iterations[0]); // IC(0) beats Jacobi
    EXPECT_LT(iterations[3], iterations[0]); // the coarse level beats Jacobi alone
}

TEST(PressureSolver, WarmStartAtTheSolutionNeedsNoIteration) {
    PressureSolver s = makeSolver(Preconditioner::TwoLevel);
    const Eigen::MatrixXd dense = fillSystem(s);
    const Eigen::VectorXd exact = dense.llt().solve(asVector(s.rhs(), kNx * kNy));
    for (int i = 0; i < kNx * kNy; ++i)
        s.solution()[static_cast<std::size_t>(i)] = exact[i];
    const PressureSolveResult res = s.solve();
    EXPECT_EQ(res.status, PressureSolveStatus::Converged);
    EXPECT_EQ(res.iterations, 0);
}

TEST(PressureSolver, ZeroRightHandSideGivesZero) {
    PressureSolver s = makeSolver(Preconditioner::IncompleteCholesky);
    fillSystem(s);
    for (int i = 0; i < kNx * kNy; ++i) {
        s.rhs()[static_cast<std::size_t>(i)] = 0.0;
        s.solution()[static_cast<std::size_t>(i)] = 1.0;
    }
    const PressureSolveResult res = s.solve();
    EXPECT_EQ(res.status, PressureSolveStatus::Converged);
    EXPECT_EQ(res.iterations, 0);
    EXPECT_EQ(res.relativeResidual, 0.0);
    for (int i = 0; i < kNx * kNy; ++i)
        EXPECT_EQ(s.solution()[static_cast<std::size_t>(i)], 0.0);
}

TEST(PressureSolver, ReportsNonFiniteAndUnconvergedSolves) {
    PressureSolver bad = makeSolver(Preconditioner::Jacobi);
    fillSystem(bad);
    bad.rhs()[5] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(bad.solve().status, PressureSolveStatus::NonFiniteRhs);

    PressureSolver slow = makeSolver(Preconditioner::Jacobi, 1e-14, 2);
    fillSystem(slow);
    const PressureSolveResult res = slow.solve();
    EXPECT_EQ(res.status, PressureSolveStatus::NotConverged);
    EXPECT_EQ(res.iterations, 2);
    EXPECT_GT(res.relativeResidual, 1e-14);
    EXPECT_LT(res.worstRow, static_cast<std::size_t>(kNx * kNy));
}

TEST(PressureSolver, RejectsUnusableSettings) {
    EXPECT_THROW(PressureSolver(Preconditioner::Jacobi, 0.0, 10, 4, 4, 1, 1),
                 std::invalid_argument);
    EXPECT_THROW(PressureSolver(Preconditioner::Jacobi, 1e-6, 0, 4, 4, 1, 1),
                 std::invalid_argument);
}
