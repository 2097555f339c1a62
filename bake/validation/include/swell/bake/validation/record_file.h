#pragma once
// The records of experiments the validation compares runs with, read at run time from CSV files
// in the validation data folder (bake/validation/data in the source tree, share/swell/validation
// beside the programs' bin folder in the build and the installed tree). A record file opens with
// '#' comment lines that cite the source of its numbers; its first other line names the columns
// and each further line is one row of as many comma-separated fields.

#include <cstddef>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace swell::bake::validation {

/// A record file that is missing or cannot be read as its loader expects. The message names the
/// file and, where there is one, the line.
class RecordFileError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// One row of a record file: its fields in the order of the header's columns.
struct RecordRow {
    std::size_t line = 0; ///< 1-based line number in the file
    std::vector<std::string> fields;
};

/// A record file as read: its rows in file order.
struct RecordFile {
    std::filesystem::path path;
    std::vector<RecordRow> rows;

    /// Field `column` of `row` as a finite number; throws RecordFileError naming the file, the
    /// line and the column for anything else (an empty field, trailing text, inf, nan).
    double number(const RecordRow& row, std::size_t column) const;
    /// RecordFileError "FILE:LINE: problem" for a loader's own checks on a row.
    RecordFileError error(const RecordRow& row, const std::string& problem) const;
};

/// Reads the record file `path`, whose header must name exactly `columns`, in that order.
/// Throws RecordFileError for a file that cannot be opened, another header, a row with another
/// number of fields, or no rows at all.
RecordFile readRecordFile(const std::filesystem::path& path,
                          std::span<const std::string_view> columns);

/// The folder of the record files: $SWELL_VALIDATION_DATA when it is set and not empty, else
/// share/swell/validation beside the bin folder of the running program.
std::filesystem::path validationDataDir();

/// readRecordFile(validationDataDir() / name, columns).
RecordFile readValidationRecords(std::string_view name, std::span<const std::string_view> columns);

} // namespace swell::bake::validation
