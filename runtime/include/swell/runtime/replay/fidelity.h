#pragma once
// Fidelity of the replay against the simulated surface it replays (docs/runtime.md,
// "Fidelity"): a row of the height field, as the mesh draws it (linear between cell centres),
// against a frame's free surface eta(x) (the upper envelope of its surface particles,
// surface_envelope.h, or an analytic surface), sampled every `step` metres.

#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/surface_envelope.h"

#include <cstddef>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <span>

namespace swell::runtime {

/// One row against one surface.
struct RowFidelity {
    double sumSquares = 0.0; ///< sum of squared differences (m^2)
    std::size_t samples = 0; ///< points compared
    double maxAbs = 0.0;     ///< largest |row - eta| (m)
    /// (max eta - max row) / (max eta - min eta) over the points: the crest-height loss as a
    /// fraction of the crest-to-trough height (0 when eta is flat).
    double crestLoss = 0.0;
};

/// Compares `row` (grid.cellsX heights at x0 + (n + 1/2) dx, linear in between) with `eta` at
/// x = lo, lo + step, ... <= hi, clipped to the first and last column centres. Throws
/// std::invalid_argument for a row of the wrong length or a step that is not > 0.
RowFidelity compareRow(std::span<const double> row, const Grid& grid,
                       const std::function<double(double)>& eta, double lo, double hi, double step);
/// compareRow against an envelope, over the x range where it is not extrapolated.
RowFidelity compareRow(std::span<const double> row, const Grid& grid, const SurfaceEnvelope& eta,
                       double step);

/// Many rows (frames) together.
struct FidelityStats {
    std::size_t rows = 0;
    std::size_t samples = 0;
    double sumSquares = 0.0;
    double maxAbs = 0.0;    ///< worst point of any row (m)
    double sumRowMax = 0.0; ///< sum of each row's maxAbs
    double sumCrestLoss = 0.0;
    double maxCrestLoss = 0.0; ///< largest crest loss of a row

    void add(const RowFidelity& r);
    double rms() const;
    double meanRowMax() const { return rows ? sumRowMax / static_cast<double>(rows) : 0.0; }
    double meanCrestLoss() const { return rows ? sumCrestLoss / static_cast<double>(rows) : 0.0; }
};

/// Standard deviation of row m's heights (m).
double rowSpread(const HeightField& h, int m);
/// Standard deviation of every cell's height (m): how much wave a frame shows.
double fieldSpread(const HeightField& h);
/// A row whose heights spread less than this is flat (no wave on it), metres.
inline constexpr double kFlatRowMetres = 0.005;
/// Rows with rowSpread below kFlatRowMetres.
int flatRows(const HeightField& h);

/// {"rows", "samples", "rms_m", "max_m", "mean_row_max_m", "crest_loss_mean",
///  "crest_loss_max"} and, when l0 > 0, the same lengths in l0 ("rms_l0", ...).
nlohmann::json toJson(const FidelityStats& stats, double l0);

} // namespace swell::runtime
