#pragma once
// swell-validate's files: the records and series its options name (--csv, --records,
// --pressure-records), each written whole or not at all.

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "swell/bake/solver_run.h"

namespace swell::bake {

/// Writes `text` to `path` whole or not at all: to a temporary name in the same folder,
/// renamed when complete. Throws std::runtime_error naming the option, the file and the error.
void writeTextFile(const std::filesystem::path& path, const std::string& text, const char* option);

/// Writes a wave check's gauge records (GaugeRecords) to `path` as CSV: a column t (s), then one
/// per gauge, named by `columns`, of the elevations (m).
void writeGaugeSeries(const std::filesystem::path& path, const GaugeRecords& r,
                      const std::vector<std::string>& columns);

/// The same with one column per gauge at x (m), named PREFIX_x.
void writeGaugeSeries(const std::filesystem::path& path, const GaugeRecords& r,
                      const std::string& prefix, std::span<const double> gauges);

/// What a wave check's report says of its run (addGaugeRun) and, where `csv` names a file, its
/// gauge series there (one column PREFIX_x per gauge).
void addGaugeRun(nlohmann::json& out, const GaugeRecords& r, const std::vector<double>& gauges,
                 const std::string& csv, const std::string& prefix);

} // namespace swell::bake
