#pragma once
// The water-level gauges of the Lobovsky et al. (2014) dam break: the experiment's records, read
// from the validation data folder (record_file.h), and its tank. Data only; validation.h compares
// a run with it.

#include <span>
#include <string>
#include <string_view>

namespace swell::bake::validation {

/// One sample of a water-level gauge record: time since the gate release and water height.
struct LevelPoint {
    double t = 0.0; ///< (s)
    double h = 0.0; ///< (m), measured from the tank floor
};

/// A water-level gauge of the Lobovsky et al. (2014) dam break and its experimental record.
struct LevelGauge {
    std::string name;
    double x = 0.0; ///< (m), from the tank's left (upstream) wall, i.e. the wall behind the column
    std::span<const LevelPoint> series;
    /// The same gauge's record in the experiment's other series, on the same times; empty where
    /// none is stored. Only to measure the experiment's repeatability (lobovskyScatter).
    std::span<const LevelPoint> repeat;
};

/// Geometry of the 2D section of the Lobovsky et al. (2014) tank, H = 300 mm filling.
struct LobovskyGeometry {
    double tankLength = 0.0;   ///< (m), inner length between the two end walls
    double tankHeight = 0.0;   ///< (m)
    double columnLength = 0.0; ///< (m), the column fills 0 <= x <= columnLength
    double columnHeight = 0.0; ///< (m), H
};

/// L. Lobovsky, E. Botia-Vera, F. Castellana, J. Mas-Soler, A. Souto-Iglesias, "Experimental
/// investigation of dynamic pressure loads during dam break", J. Fluids Struct. 48 (2014)
/// 407-434, H = 300 mm case. Lengths from the TNL-SPH example of this case (TNL-Project/TNL-SPH,
/// examples/WCSPH-DBC/damBreak2D_WCSPH-DBC/init.py: box 1.61 m, fluid 0.6 m x 0.3 m). The tank
/// height 0.6 m is the paper's value as recalled, NOT confirmed by a stored source (see
/// lobovsky2014.cpp's lobovskyH300Geometry); only the walls below the splash matter for the gauges.
LobovskyGeometry lobovskyH300Geometry();

/// Water-level gauges H1..H4 of the same experiment (H = 300 mm), in the order H1, H2, H3, H4,
/// at x = 0.3, 0.865, 1.114, 1.3625 m from the upstream wall. The records are the
/// experimental files (Fig. 16 of the paper) shipped with TNL-SPH, converted from
/// t sqrt(g/H), h/H to seconds and metres and thinned; the data file names the exact
/// files, commits and conversion. They cover 0 <= t <= 1.963 s. H2-H4 also carry the other
/// series' record (`repeat`, "ETSIN 01" against "ETSIN 02"). Read on first use; throws
/// RecordFileError when the file is missing or damaged.
std::span<const LevelGauge> lobovskyH300Gauges();

/// The record file of lobovskyH300Gauges, in the validation data folder.
inline constexpr std::string_view kLobovskyH300LevelsFile = "lobovsky2014_h300_levels.csv";

} // namespace swell::bake::validation
