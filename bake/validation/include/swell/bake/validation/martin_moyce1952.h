#pragma once
// The dam-break surge front of Martin & Moyce (1952): the experiment's record, read from the
// validation data folder (record_file.h). Data only; validation.h compares a run with it.

#include <span>
#include <string_view>

namespace swell::bake::validation {

/// One experimental point of the dam-break surge front: T = t sqrt(2 g / a), Z = z / a.
struct FrontPoint {
    double T = 0.0;
    double Z = 0.0;
};

/// The record file, in the validation data folder.
inline constexpr std::string_view kMartinMoyceFile = "martin_moyce_1952.csv";

/// J. C. Martin, W. J. Moyce, "Part IV. An experimental study of the collapse of liquid columns
/// on a rigid horizontal plane", Phil. Trans. R. Soc. Lond. A 244 (1952) 312-324, Fig. 3,
/// column of height 2a (n^2 = 2): surge front Z against T for a = 2.25 in, as digitised in
/// PySPH (pysph/examples/db_exp_data.py, "mm_data_2"). Read on first use; throws
/// RecordFileError when the file is missing or damaged.
std::span<const FrontPoint> martinMoyceA225();
/// Same figure and source, a = 1.125 in ("mm_data_1").
std::span<const FrontPoint> martinMoyceA1125();

} // namespace swell::bake::validation
