#pragma once
// Measures of a replayed picture that a viewer's eye reacts to (docs/runtime.md, "Picture
// check"), on height fields of the base mesh and on splash sprite positions:
//  * Slope ratios: mean |dh/dz| / mean |dh/dx| and the 99th percentile of |dh/dz| over that of
//    |dh/dx|, one-cell differences over the inner cells (a margin of the mesh left out on each
//    side). Waves running along x with long crests along z give 0.15 - 0.6; a field striped
//    by its slices gives more than 1.
//  * Needle share: the share of cells more than a threshold above all four neighbours or
//    below all four (the edge cells, which lack a neighbour, are not counted).
//  * Share differing: the share of cells where two fields differ by more than a threshold
//    (e.g. two seeds: visibly different surfaces).
//  * Mean change: mean |a - b| over the cells (frame to frame).
//  * Disc mean: the mean height of the cells whose centres lie within a radius of a point
//    (the whirlpool's eye).
//  * Crease ratio: the mean |second difference| across a straight line (cells within 1.5
//    cells of it, differences along the grid axis nearer its normal) over the mean beside it
//    (cells 3 to 8 cells from it): a slope break along the line gives more than 1.
//  * Line coverage: how much of one straight line the points cover: over every direction in
//    1-degree steps and offsets in bins of a half-width w (a line covers two neighbouring
//    bins), the most bins of width 2 w along the line that hold a point, times 2 w, over a
//    span (the mesh's longer side); at most 1. Sparse splashes give a small coverage; spray
//    repeated at one place in every slice makes a row of sprites across the mesh, near 1.

#include "swell/runtime/replay/height_field.h"

#include <span>

namespace swell::runtime {

struct SlopeRatios {
    double mean = 0.0; ///< mean |dh/dz| / mean |dh/dx|
    double p99 = 0.0;  ///< 99th percentile of |dh/dz| / that of |dh/dx|
};

/// Slope ratios over the cells at least `margin` x (N, M) from the sides. Throws
/// std::invalid_argument when fewer than 2 x 2 cells remain or the field is flat along x.
SlopeRatios slopeRatios(const HeightField& h, double margin = 0.1);
double needleShare(const HeightField& h, double threshold);
/// Throws std::invalid_argument when the sizes differ.
double shareDiffering(const HeightField& a, const HeightField& b, double threshold);
/// Throws std::invalid_argument when the sizes differ.
double meanChange(const HeightField& a, const HeightField& b);
/// Cell (n, m) has its centre at (n + 1/2, m + 1/2) in cells; centre and radius in cells.
/// Throws std::invalid_argument when no cell lies within the disc.
double discMean(const HeightField& h, double cn, double cm, double radius);
/// The line through (pn, pm) along direction (tn, tm), in cells. Throws
/// std::invalid_argument when fewer than 4 cells lie on either side of the comparison.
double creaseRatio(const HeightField& h, double pn, double pm, double tn, double tm);
/// Points (xs[i], zs[i]), metres; 0 when there are none.
double lineCoverage(std::span<const double> xs, std::span<const double> zs, double halfWidth,
                    double span);

} // namespace swell::runtime
