// The pressure Poisson solve (pressure_solver.h): preconditioned conjugate gradient, the
// Jacobi, symmetric Gauss-Seidel, IC(0) and two-level preconditioners, and the band Cholesky
// factor of the two-level coarse matrix.
#include "swell/bake/pressure_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "parallel_thresholds.h"

namespace swell::bake {
namespace {

// Sums run in index order on one thread, whatever the thread count: an OpenMP reduction
// would add per-thread partial sums, whose rounding depends on how many threads there are, and
// the flow amplifies that last bit into a different bake (numerics_version.h). The in-order
// sum is also what one thread computed before, so the numbers of a one-thread bake are
// unchanged. Its cost is one pass of n dependent additions, beside a matrix-vector product of
// about 30 multiply-adds per row.
double dot(const double* a, const double* b, std::size_t n) {
    double s = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        s += a[i] * b[i];
    return s;
}

} // namespace

double SparseRows::multiply(const double* v, double* out) const {
    const int n = static_cast<int>(rows);
#pragma omp parallel for schedule(static) if (static_cast <std::size_t>(n) >= kParallelMin)
    for (int r = 0; r < n; ++r) {
        const int end = rowEnd(r);
        double s = 0.0;
        for (int k = rowPtr[static_cast<std::size_t>(r)]; k < end; ++k) {
            s += val[static_cast<std::size_t>(k)] * v[col[static_cast<std::size_t>(k)]];
        }
        out[r] = s;
    }
    return dot(v, out, rows); // in order: the same v.Av with any thread count
}

PressureSolver::PressureSolver(Preconditioner preconditioner, double tolerance, int maxIterations,
                               std::size_t maxRows, std::size_t maxRowEntries, int cellsX,
                               int cellsY)
    : m_preconditioner(preconditioner), m_tolerance(tolerance), m_maxIterations(maxIterations),
      m_cellsX(cellsX) {
    if (!(tolerance > 0.0) || maxIterations <= 0 || cellsX <= 0 || cellsY <= 0) {
        throw std::invalid_argument("PressureSolver: tolerance, iterations and grid must be "
                                    "positive");
    }
    const std::size_t n = maxRows;
    const std::size_t cap = n * maxRowEntries;
    m_a.rowPtr.assign(n + 1, 0);
    m_a.rowNnz.assign(n, 0);
    m_a.col.assign(cap, 0);
    m_a.val.assign(cap, 0.0);
    m_a.diagPos.assign(n, 0);
    m_ic.assign(cap, 0.0);
    m_icMark.assign(n, -1);
    m_rowCell.assign(n, 0);
    m_aggMap.assign(static_cast<std::size_t>(cellsX) * static_cast<std::size_t>(cellsY), -1);
    m_aggOf.assign(n, 0);
    m_rc.assign(n, 0.0);
    m_zc.assign(n, 0.0);
    m_band.assign(std::min<std::size_t>(n * 64, std::size_t{1} << 22), 0.0);
    for (auto* v : {&m_b, &m_x, &m_r, &m_z, &m_d, &m_q, &m_invDiag})
        v->assign(n, 0.0);
}

void PressureSolver::factorIncompleteCholesky() {
    // IC(0): L L^T ~ A with L on A's lower pattern. Row-by-row (up-looking):
    //   L_ij = (A_ij - sum_{k<j} L_ik L_jk) / L_jj,  L_ii = sqrt(A_ii - sum_{k<i} L_ik^2).
    // A is a diagonally dominant M-matrix, so no pivot can vanish.
    const int rows = static_cast<int>(m_a.rows);
    const auto at = [](auto& v, int k) -> auto& {
        return v[static_cast<std::size_t>(k)];
    };
    for (int i = 0; i < rows; ++i) {
        const int begin = at(m_a.rowPtr, i);
        const int dpos = at(m_a.diagPos, i);
        for (int k = begin; k < dpos; ++k)
            at(m_icMark, at(m_a.col, k)) = k;
        double diagSum = 0.0;
        for (int k = begin; k < dpos; ++k) {
            const int j = at(m_a.col, k);
            double s = at(m_a.val, k);
            const int jb = at(m_a.rowPtr, j);
            const int jd = at(m_a.diagPos, j);
            for (int q = jb; q < jd; ++q) { // sum over k < j present in both rows
                const int pos = at(m_icMark, at(m_a.col, q));
                if (pos >= 0)
                    s -= at(m_ic, pos) * at(m_ic, q);
            }
            const double lij = s / at(m_ic, jd);
            at(m_ic, k) = lij;
            diagSum += lij * lij;
        }
        const double pivot = at(m_a.val, dpos) - diagSum;
        // Safeguard (never expected for an M-matrix): fall back to the diagonal.
        at(m_ic, dpos) = pivot > 0.0 ? std::sqrt(pivot) : std::sqrt(at(m_a.val, dpos));
        for (int k = begin; k < dpos; ++k)
            at(m_icMark, at(m_a.col, k)) = -1;
    }
}

void PressureSolver::setupTwoLevel() {
    // Aggregates: one per grid cell holding unknowns, numbered along the shorter side of the
    // occupied cells first, so the coarse matrix (cells couple only to adjacent cells) has a
    // band about as wide as the shorter side.
    const int rows = static_cast<int>(m_a.rows);
    const int nx = m_cellsX;
    int x0 = nx, x1 = -1, y0 = static_cast<int>(m_aggMap.size()) / nx, y1 = -1;
    for (int r = 0; r < rows; ++r) {
        const std::uint32_t cell = m_rowCell[static_cast<std::size_t>(r)];
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
                if (id == -2)
                    id = nAgg++;
            }
        }
    } else { // tall: row by row
        for (int cy = y0; cy <= y1; ++cy) {
            for (int cx = x0; cx <= x1; ++cx) {
                int& id = m_aggMap[static_cast<std::size_t>(cy * nx + cx)];
                if (id == -2)
                    id = nAgg++;
            }
        }
    }
    for (int r = 0; r < rows; ++r) {
        m_aggOf[static_cast<std::size_t>(r)] = m_aggMap[m_rowCell[static_cast<std::size_t>(r)]];
    }
    for (int r = 0; r < rows; ++r)
        m_aggMap[m_rowCell[static_cast<std::size_t>(r)]] = -1;
    m_nAgg = nAgg;
    int bw = 0;
    for (int r = 0; r < rows; ++r) {
        const int I = m_aggOf[static_cast<std::size_t>(r)];
        for (int k = m_a.rowPtr[static_cast<std::size_t>(r)]; k < m_a.rowEnd(r); ++k) {
            bw = std::max(
                bw, I - m_aggOf[static_cast<std::size_t>(m_a.col[static_cast<std::size_t>(k)])]);
        }
    }
    m_bandwidth = bw;
    const std::size_t width = static_cast<std::size_t>(bw) + 1;
    const std::size_t need = static_cast<std::size_t>(nAgg) * width;
    if (m_band.size() < need)
        m_band.resize(need); // grows only for an unusually wide band
    double* band = m_band.data();
    // Coarse matrix A_c = P^T A P (P: piecewise constant on aggregates), lower band only:
    // band[I * width + (I - J)] = sum of A_ij over i in I, j in J.
    // A row's columns of one aggregate come one after another (columns are sorted, rows are
    // in cell order), so each run is summed in a register and stored once: the same additions
    // in the same order as adding each into the band.
    std::fill(band, band + need, 0.0);
    for (int r = 0; r < rows; ++r) {
        const int I = m_aggOf[static_cast<std::size_t>(r)];
        double* rowI = band + static_cast<std::size_t>(I) * width;
        int runJ = -1;
        double sum = 0.0;
        for (int k = m_a.rowPtr[static_cast<std::size_t>(r)]; k < m_a.rowEnd(r); ++k) {
            const int J = m_aggOf[static_cast<std::size_t>(m_a.col[static_cast<std::size_t>(k)])];
            if (J > I)
                continue;
            if (J != runJ) {
                if (runJ >= 0)
                    rowI[I - runJ] = sum;
                runJ = J;
                sum = rowI[I - J];
            }
            sum += m_a.val[static_cast<std::size_t>(k)];
        }
        if (runJ >= 0)
            rowI[I - runJ] = sum;
    }
    // Band Cholesky in place: L(i, j) at band[i * width + (i - j)].
    for (int i = 0; i < nAgg; ++i) {
        double* Li = band + static_cast<std::size_t>(i) * width;
        for (int j = std::max(0, i - bw); j <= i; ++j) {
            const double* Lj = band + static_cast<std::size_t>(j) * width;
            double s = Li[i - j];
            for (int k = std::max(0, i - bw); k < j; ++k)
                s -= Li[i - k] * Lj[j - k];
            if (j == i) {
                Li[0] = std::sqrt(std::max(s, 1e-300)); // SPD: s > 0 up to round-off
            } else {
                Li[i - j] = s / Lj[0];
            }
        }
    }
}

void PressureSolver::applyTwoLevel(const double* r, double* z) const {
    // z = D^-1 r + P A_c^-1 P^T r (additive two-level, symmetric positive definite).
    const int rows = static_cast<int>(m_a.rows);
    const int nAgg = m_nAgg;
    const int bw = m_bandwidth;
    const std::size_t width = static_cast<std::size_t>(bw) + 1;
    const double* band = m_band.data();
    double* rc = m_rc.data();
    double* zc = m_zc.data();
    // rc = P^T r. The rows of one aggregate come one after another (rows in cell order), so
    // each run is summed in a register: the same additions in the same order.
    std::fill(rc, rc + nAgg, 0.0);
    for (int q = 0; q < rows;) {
        const int I = m_aggOf[static_cast<std::size_t>(q)];
        double sum = rc[I];
        for (; q < rows && m_aggOf[static_cast<std::size_t>(q)] == I; ++q)
            sum += r[q];
        rc[I] = sum;
    }
    for (int i = 0; i < nAgg; ++i) { // L y = rc
        const double* Li = band + static_cast<std::size_t>(i) * width;
        double s = rc[i];
        for (int k = std::max(0, i - bw); k < i; ++k)
            s -= Li[i - k] * zc[k];
        zc[i] = s / Li[0];
    }
    for (int i = nAgg - 1; i >= 0; --i) { // L^T zc = y
        double s = zc[i];
        for (int k = i + 1; k <= std::min(nAgg - 1, i + bw); ++k) {
            s -=
                band[static_cast<std::size_t>(k) * width + static_cast<std::size_t>(k - i)] * zc[k];
        }
        zc[i] = s / band[static_cast<std::size_t>(i) * width];
    }
#pragma omp parallel for schedule(static) if (static_cast <std::size_t>(rows) >= kParallelVector)
    for (int q = 0; q < rows; ++q) {
        z[q] = r[q] * m_invDiag[static_cast<std::size_t>(q)] +
               zc[m_aggOf[static_cast<std::size_t>(q)]];
    }
}

void PressureSolver::applySymmetricGaussSeidel(const double* r, double* z) const {
    // M = (D + L) D^-1 (D + U), U = L^T: forward sweep (D + L) y = r, then backward
    // sweep (D + U) z = D y, i.e. z_i = y_i - (sum_{j>i} a_ij z_j) / a_ii.
    const int rows = static_cast<int>(m_a.rows);
    for (int i = 0; i < rows; ++i) {
        double s = r[i];
        const int dpos = m_a.diagPos[static_cast<std::size_t>(i)];
        for (int k = m_a.rowPtr[static_cast<std::size_t>(i)]; k < dpos; ++k) {
            s -= m_a.val[static_cast<std::size_t>(k)] * z[m_a.col[static_cast<std::size_t>(k)]];
        }
        z[i] = s * m_invDiag[static_cast<std::size_t>(i)];
    }
    for (int i = rows - 1; i >= 0; --i) {
        double s = 0.0;
        const int dpos = m_a.diagPos[static_cast<std::size_t>(i)];
        for (int k = dpos + 1; k < m_a.rowEnd(i); ++k) {
            s += m_a.val[static_cast<std::size_t>(k)] * z[m_a.col[static_cast<std::size_t>(k)]];
        }
        z[i] -= s * m_invDiag[static_cast<std::size_t>(i)];
    }
}

void PressureSolver::applyIncompleteCholesky(const double* r, double* z) const {
    // Forward solve L y = r (y stored in z), then backward L^T z = y.
    const int rows = static_cast<int>(m_a.rows);
    for (int i = 0; i < rows; ++i) {
        double s = r[i];
        const int dpos = m_a.diagPos[static_cast<std::size_t>(i)];
        for (int k = m_a.rowPtr[static_cast<std::size_t>(i)]; k < dpos; ++k) {
            s -= m_ic[static_cast<std::size_t>(k)] * z[m_a.col[static_cast<std::size_t>(k)]];
        }
        z[i] = s / m_ic[static_cast<std::size_t>(dpos)];
    }
    for (int i = rows - 1; i >= 0; --i) {
        const int dpos = m_a.diagPos[static_cast<std::size_t>(i)];
        const double zi = z[i] / m_ic[static_cast<std::size_t>(dpos)];
        z[i] = zi;
        for (int k = m_a.rowPtr[static_cast<std::size_t>(i)]; k < dpos; ++k) {
            z[m_a.col[static_cast<std::size_t>(k)]] -= m_ic[static_cast<std::size_t>(k)] * zi;
        }
    }
}

void PressureSolver::applyPreconditioner(const double* r, double* z) const {
    switch (m_preconditioner) {
    case Preconditioner::TwoLevel:
        applyTwoLevel(r, z);
        return;
    case Preconditioner::Jacobi: {
        const int rows = static_cast<int>(m_a.rows);
#pragma omp parallel for schedule(static) if (static_cast <std::size_t>(rows) >= kParallelMin)
        for (int i = 0; i < rows; ++i)
            z[i] = r[i] * m_invDiag[static_cast<std::size_t>(i)];
        return;
    }
    case Preconditioner::SymmetricGaussSeidel:
        applySymmetricGaussSeidel(r, z);
        return;
    case Preconditioner::IncompleteCholesky:
        applyIncompleteCholesky(r, z);
        return;
    }
}

PressureSolveResult PressureSolver::solve() {
    // Preconditioned conjugate gradient on the SPD system A x = b, warm-started.
    PressureSolveResult result;
    const std::size_t n = m_a.rows;
    if (n == 0)
        return result;
    for (std::size_t r = 0; r < n; ++r) {
        m_invDiag[r] = 1.0 / m_a.val[static_cast<std::size_t>(m_a.diagPos[r])];
    }
    if (m_preconditioner == Preconditioner::IncompleteCholesky)
        factorIncompleteCholesky();
    if (m_preconditioner == Preconditioner::TwoLevel)
        setupTwoLevel();
    double* x = m_x.data();
    double* r = m_r.data();
    double* z = m_z.data();
    double* d = m_d.data();
    double* q = m_q.data();
    const double* b = m_b.data();
    const double bNorm = std::sqrt(dot(b, b, n));
    if (bNorm == 0.0) {
        std::fill(x, x + n, 0.0);
        return result;
    }
    if (!std::isfinite(bNorm)) {
        result.status = PressureSolveStatus::NonFiniteRhs;
        return result;
    }
    m_a.multiply(x, q);
#pragma omp parallel for schedule(static) if (n >= kParallelVector)
    for (std::size_t i = 0; i < n; ++i)
        r[i] = b[i] - q[i];
    double rNorm = std::sqrt(dot(r, r, n));
    const double target = m_tolerance * bNorm;
    int it = 0;
    if (rNorm > target) {
        applyPreconditioner(r, z);
        std::copy(z, z + n, d);
        double rz = dot(r, z, n);
        while (it < m_maxIterations) {
            const double alpha = rz / m_a.multiply(d, q); // q = A d and d.q in one sweep
#pragma omp parallel for schedule(static) if (n >= kParallelVector)
            for (std::size_t i = 0; i < n; ++i) {
                x[i] += alpha * d[i];
                r[i] -= alpha * q[i];
            }
            ++it;
            rNorm = std::sqrt(dot(r, r, n));
            if (!(rNorm > target))
                break; // also stops on NaN, caught below
            applyPreconditioner(r, z);
            const double rzNew = dot(r, z, n);
            const double beta = rzNew / rz;
            rz = rzNew;
#pragma omp parallel for schedule(static) if (n >= kParallelVector)
            for (std::size_t i = 0; i < n; ++i)
                d[i] = z[i] + beta * d[i];
        }
    }
    result.iterations = it;
    result.relativeResidual = rNorm / bNorm;
    if (!std::isfinite(rNorm)) {
        result.status = PressureSolveStatus::NonFinite;
    } else if (rNorm > target) {
        std::size_t worst = 0;
        for (std::size_t i = 1; i < n; ++i) {
            if (std::abs(r[i]) > std::abs(r[worst]))
                worst = i;
        }
        result.status = PressureSolveStatus::NotConverged;
        result.worstRow = worst;
    }
    return result;
}

} // namespace swell::bake
