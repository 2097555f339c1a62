#include "report_files.h"

#include "report_figures.h"

#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "swell/cache/checked_write.h"

namespace swell::bake {

void writeTextFile(const std::filesystem::path& path, const std::string& text, const char* option) {
    if (const swell::cache::ReplaceResult r =
            swell::cache::replaceFile(path, text.data(), text.size());
        r.error != 0) {
        throw std::runtime_error(
            fmt::format("{} {}: cannot write: {}", option, path.string(), std::strerror(r.error)));
    }
}

void writeGaugeSeries(const std::filesystem::path& path, const GaugeRecords& r,
                      const std::vector<std::string>& columns) {
    std::string text = "t";
    for (const std::string& c : columns)
        text += "," + c;
    text += '\n';
    for (std::size_t k = 0; k < r.times.size(); ++k) {
        text += fmt::format("{:.5f}", r.times[k]);
        for (const std::vector<double>& e : r.elevations)
            text += fmt::format(",{:.6f}", e[k]);
        text += '\n';
    }
    writeTextFile(path, text, "--csv");
}

void writeGaugeSeries(const std::filesystem::path& path, const GaugeRecords& r,
                      const std::string& prefix, std::span<const double> gauges) {
    std::vector<std::string> columns;
    for (double x : gauges)
        columns.push_back(fmt::format("{}_{}", prefix, x));
    writeGaugeSeries(path, r, columns);
}

void addGaugeRun(nlohmann::json& out, const GaugeRecords& r, const std::vector<double>& gauges,
                 const std::string& csv, const std::string& prefix) {
    addGaugeRun(out, r, gauges);
    if (!csv.empty())
        writeGaugeSeries(csv, r, prefix, gauges);
}

} // namespace swell::bake
