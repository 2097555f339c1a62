#include "swell/bake/validation/record_file.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <system_error>

namespace swell::bake::validation {
namespace {

std::vector<std::string> splitFields(const std::string& line) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(line.substr(start, comma - start));
        if (comma == std::string::npos)
            return fields;
        start = comma + 1;
    }
}

std::string joined(std::span<const std::string_view> columns) {
    std::string s;
    for (const std::string_view c : columns)
        s.append(s.empty() ? "" : ",").append(c);
    return s;
}

} // namespace

double RecordFile::number(const RecordRow& row, std::size_t column) const {
    const std::string& field = row.fields.at(column);
    double value = 0.0;
    const char* end = field.data() + field.size();
    const auto [ptr, ec] = std::from_chars(field.data(), end, value);
    if (field.empty() || ec != std::errc{} || ptr != end || !std::isfinite(value))
        throw error(row, "column " + std::to_string(column + 1) + ": '" + field +
                             "' is not a finite number");
    return value;
}

RecordFileError RecordFile::error(const RecordRow& row, const std::string& problem) const {
    return RecordFileError(path.string() + ":" + std::to_string(row.line) + ": " + problem);
}

RecordFile readRecordFile(const std::filesystem::path& path,
                          std::span<const std::string_view> columns) {
    std::ifstream in(path);
    if (!in)
        throw RecordFileError(path.string() +
                              ": cannot open the record file (is SWELL_VALIDATION_DATA or the "
                              "share/swell/validation folder beside bin/ right?)");
    RecordFile file{path, {}};
    bool header = false;
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        if (line.empty() || line.front() == '#')
            continue;
        const std::string where = path.string() + ":" + std::to_string(number) + ": ";
        if (!header) {
            if (line != joined(columns))
                throw RecordFileError(where + "header '" + line + "', expected '" +
                                      joined(columns) + "'");
            header = true;
            continue;
        }
        RecordRow row{number, splitFields(line)};
        if (row.fields.size() != columns.size())
            throw RecordFileError(where + std::to_string(row.fields.size()) + " fields, expected " +
                                  std::to_string(columns.size()));
        file.rows.push_back(std::move(row));
    }
    if (!header)
        throw RecordFileError(path.string() + ": no header line");
    if (file.rows.empty())
        throw RecordFileError(path.string() + ": no rows");
    return file;
}

std::filesystem::path validationDataDir() {
    if (const char* dir = std::getenv("SWELL_VALIDATION_DATA"); dir && *dir)
        return dir;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec)
        throw RecordFileError("cannot find the running program (/proc/self/exe: " + ec.message() +
                              "); set SWELL_VALIDATION_DATA to the validation data folder");
    return exe.parent_path().parent_path() / "share" / "swell" / "validation";
}

RecordFile readValidationRecords(std::string_view name, std::span<const std::string_view> columns) {
    return readRecordFile(validationDataDir() / name, columns);
}

} // namespace swell::bake::validation
