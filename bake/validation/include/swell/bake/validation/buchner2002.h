#pragma once
// The pressure on the far wall of the dam break of Buchner (2002), sensor P1: the experiment's
// record and Marrone et al. (2011)'s delta-SPH solutions of the same 2D flow at three
// resolutions. Its tank is the Lobovsky et al. (2014) tank at twice the size (a column 2H long
// and H high in a tank 5.366 H long; H = 0.6 m against Lobovsky's 0.3 m), so under Froude
// scaling the Lobovsky scene is the same flow and its far-wall pressure can be compared in
// t sqrt(g / H) and p / (rho g H). Data only, read from the validation data folder
// (record_file.h); wall_pressure.h compares a run with it.

#include <span>
#include <string_view>

namespace swell::bake::validation {

/// One row of the P1 records, in the dimensionless units of the sources.
struct FarWallPressureSample {
    double t = 0.0;           ///< t sqrt(g / H)
    double experiment = 0.0;  ///< Buchner (2002), p / (rho g H)
    double deltaSph40 = 0.0;  ///< Marrone et al. (2011), delta-SPH at H / dx = 40
    double deltaSph80 = 0.0;  ///< the same at H / dx = 80
    double deltaSph320 = 0.0; ///< the same at H / dx = 320, their finest
};

/// Sensor P1: on the far (downstream) wall, its top at 160 / 600 H above the floor and 90 / 600 H
/// tall, as TrixiParticles.jl's setup of this case places it (validation/dam_break_2d/
/// setup_marrone_2011.jl: "the top of the sensors is at the position where the middle of the
/// sensors is in the experiment", after Adami, Hu & Adams 2012 and Greco).
inline constexpr double kBuchnerP1TopOverH = 160.0 / 600.0;
inline constexpr double kBuchnerP1HeightOverH = 90.0 / 600.0;

/// The record file, in the validation data folder.
inline constexpr std::string_view kBuchnerP1File = "buchner2002_p1.csv";

/// B. Buchner, "Green water on ship-type offshore structures", PhD thesis, Delft University of
/// Technology (2002): the P1 record; and S. Marrone, M. Antuono, A. Colagrossi, G. Colicchio,
/// D. Le Touze, G. Graziani, "delta-SPH model for simulating violent impact flows", Comput.
/// Methods Appl. Mech. Engrg. 200 (2011) 1526-1542, doi:10.1016/j.cma.2010.12.016: their P1 at
/// H / dx = 40, 80 and 320. The digitisation stored with TrixiParticles.jl, every row, t from
/// 2.005 to 7.315 (the data file names the source file, commit and columns). Read on first
/// use; throws RecordFileError when the file is missing or damaged.
std::span<const FarWallPressureSample> buchnerP1Records();

} // namespace swell::bake::validation
