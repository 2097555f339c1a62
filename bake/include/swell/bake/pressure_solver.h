#pragma once
// The pressure Poisson solve of the MPS step: a preconditioned conjugate gradient on a sparse
// symmetric positive definite matrix, with four preconditioners (mps_params.h). Knows nothing
// of particles: the solver assembles the matrix into matrix(), the right-hand side into rhs()
// and the warm start into solution(), then calls solve().
#include <cstddef>
#include <cstdint>
#include <vector>

#include "swell/bake/mps_params.h"

namespace swell::bake {

/// A sparse matrix in row storage with room to spare in every row (Eigen's uncompressed
/// layout): row r holds rowNnz[r] entries from rowPtr[r] on, columns sorted, and its diagonal
/// at diagPos[r]. Sized once; only the first `rows` rows are in use.
struct SparseRows {
    std::vector<int> rowPtr;  ///< start of each row (rows + 1 entries in use)
    std::vector<int> rowNnz;  ///< used entries of each row
    std::vector<int> col;     ///< column of each entry
    std::vector<double> val;  ///< value of each entry
    std::vector<int> diagPos; ///< position of the diagonal entry of each row
    std::size_t rows = 0;

    /// One past the last used entry of row r.
    int rowEnd(int r) const {
        return rowPtr[static_cast<std::size_t>(r)] + rowNnz[static_cast<std::size_t>(r)];
    }
    /// out = A v; returns v.out, summed in index order (the same bits with any thread count).
    double multiply(const double* v, double* out) const;
};

/// How a solve ended.
enum class PressureSolveStatus {
    Converged,    ///< |b - Ax| <= tolerance |b| (also b = 0: x = 0)
    NonFiniteRhs, ///< b holds NaN/Inf; nothing was solved
    NonFinite,    ///< the iteration produced NaN/Inf
    NotConverged, ///< maxIterations reached above the tolerance
};

/// Outcome of one solve.
struct PressureSolveResult {
    PressureSolveStatus status = PressureSolveStatus::Converged;
    int iterations = 0;
    double relativeResidual = 0.0; ///< |b - Ax| / |b| (0 for b = 0)
    std::size_t worstRow = 0;      ///< NotConverged: the row of the largest residual
};

class PressureSolver {
public:
    PressureSolver() = default;
    /// Room for `maxRows` rows of up to `maxRowEntries` entries each. The two-level
    /// preconditioner aggregates the unknowns of one cell of a cellsX x cellsY grid.
    PressureSolver(Preconditioner preconditioner, double tolerance, int maxIterations,
                   std::size_t maxRows, std::size_t maxRowEntries, int cellsX, int cellsY);

    /// The matrix A, filled by the caller (rows, rowPtr, rowNnz, col, val, diagPos).
    SparseRows& matrix() { return m_a; }
    const SparseRows& matrix() const { return m_a; }
    /// Right-hand side b (first matrix().rows entries).
    std::vector<double>& rhs() { return m_b; }
    const std::vector<double>& rhs() const { return m_b; }
    /// Warm start on entry to solve(), the solution after it.
    std::vector<double>& solution() { return m_x; }
    const std::vector<double>& solution() const { return m_x; }
    /// Grid cell of each row's unknown (read by the two-level preconditioner only).
    std::vector<std::uint32_t>& rowCells() { return m_rowCell; }

    /// Preconditioned conjugate gradient on A x = b from the warm start, until
    /// |b - Ax| <= tolerance |b| or maxIterations. Allocates nothing.
    PressureSolveResult solve();

    Preconditioner preconditioner() const { return m_preconditioner; }
    double tolerance() const { return m_tolerance; }

private:
    void factorIncompleteCholesky();
    void setupTwoLevel();
    void applyPreconditioner(const double* r, double* z) const;
    void applyTwoLevel(const double* r, double* z) const;
    void applySymmetricGaussSeidel(const double* r, double* z) const;
    void applyIncompleteCholesky(const double* r, double* z) const;

    Preconditioner m_preconditioner = Preconditioner::TwoLevel;
    double m_tolerance = 1e-6;
    int m_maxIterations = 1;
    int m_cellsX = 0;
    SparseRows m_a;
    std::vector<double> m_b, m_x;           // right-hand side, solution
    std::vector<double> m_r, m_z, m_d, m_q; // residual, preconditioned residual, direction, A d
    std::vector<double> m_invDiag;          // 1 / A_ii (Jacobi, Gauss-Seidel, two-level)
    std::vector<double> m_ic;  // IC(0) factor L (lower triangle incl. diagonal) on A's pattern
    std::vector<int> m_icMark; // column -> position scratch for the factorisation
    // Two-level preconditioner: aggregates (the unknowns of one grid cell) and the banded
    // Cholesky factor of the coarse matrix P^T A P. The band grows only when it must.
    std::vector<std::uint32_t> m_rowCell;   // grid cell of each row
    std::vector<int> m_aggMap, m_aggOf;     // grid cell -> aggregate (-1 unused); row -> aggregate
    mutable std::vector<double> m_rc, m_zc; // coarse right-hand side and solution (scratch)
    std::vector<double> m_band;
    int m_nAgg = 0;
    int m_bandwidth = 0;
};

} // namespace swell::bake
