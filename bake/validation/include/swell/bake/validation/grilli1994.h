#pragma once
// The experiment of Grilli, Subramanya, Svendsen & Veeramony (1994): a solitary wave of height
// H / h0 = 0.2 shoaling on a plane 1:34.7 beach and breaking near its last gauge, recorded by
// wave gauges on the flat bed (g0) and on the slope (g1-g9). Data only, read from the validation
// data folder (record_file.h); shoaling.h compares a run with it.

#include <span>
#include <string>
#include <string_view>

namespace swell::bake::validation {

/// One sample of a record, in the experiment's dimensionless units.
struct ShoalingSample {
    double t = 0.0;   ///< t sqrt(g / h0), on the experiment's clock
    double eta = 0.0; ///< free-surface elevation above still water / h0
};

/// A wave gauge of the experiment and its digitised record.
struct ShoalingGauge {
    std::string name;
    /// Distance from the toe of the slope / h0, positive up the beach (g0: on the flat bed).
    double xOverDepth = 0.0;
    std::span<const ShoalingSample> record;
};

/// The beach: tan(beta) = 1 / 34.7.
inline constexpr double kGrilliSlope = 1.0 / 34.7;
/// The incident wave's nominal height H / h0.
inline constexpr double kGrilliHeightOverDepth = 0.2;
/// The laboratory's still-water depth h0 (m); the records are dimensionless (Froude scaling).
inline constexpr double kGrilliDepth = 0.44;

/// The record file, in the validation data folder.
inline constexpr std::string_view kGrilli1994File = "grilli1994_h02.csv";

/// S. T. Grilli, R. Subramanya, I. A. Svendsen, J. Veeramony, "Shoaling of solitary waves on
/// plane beaches", J. Waterway, Port, Coastal, Ocean Eng. 120(6) (1994) 609,
/// doi:10.1061/(ASCE)0733-950X(1994)120:6(609); the H / h0 = 0.2 case: gauges g0, g1, g3, g5,
/// g7 and g9, in that order. The records are the
/// digitisation of the paper's figures stored with GeoscienceAustralia/ptha (SWALS example
/// dispersive/solitary_shoaling_grilli; the data file names the files, commit, positions and
/// the cuts applied). Read on first use; throws RecordFileError when the file is missing or
/// damaged. g0's record is the experiment's incident wave, on which a run's clock is
/// aligned (shoaling.h); the slope gauges' records span about 7-10 t sqrt(g / h0) around their
/// crests.
std::span<const ShoalingGauge> grilli1994Gauges();

} // namespace swell::bake::validation
