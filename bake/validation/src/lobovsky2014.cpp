#include "swell/bake/validation/lobovsky2014.h"

#include <array>
#include <cmath>
#include <string_view>
#include <vector>

#include "swell/bake/validation/record_file.h"

namespace swell::bake::validation {
namespace {

// The records are dimensionless in the file (t sqrt(g / H), h / H), as the source stores them;
// the gauges hold them in seconds and metres.
constexpr double kColumnHeight = 0.3;             // H (m)
constexpr double kSqrtGOverH = 5.718391382198319; // sqrt(9.81 / 0.3) (1/s), g = 9.81 m/s^2

/// The gauges and the storage their spans point into.
struct LobovskyRecords {
    std::vector<std::vector<LevelPoint>> series, repeat;
    std::vector<LevelGauge> gauges;
};

LobovskyRecords loadRecords() {
    static constexpr std::array<std::string_view, 5> kColumns{"gauge", "x", "kind", "t", "h"};
    const RecordFile file = readValidationRecords(kLobovskyH300LevelsFile, kColumns);
    LobovskyRecords r;
    for (const RecordRow& row : file.rows) {
        const std::string& name = row.fields[0];
        const bool repeat = row.fields[2] == "repeat";
        if (!repeat && row.fields[2] != "series")
            throw file.error(row, "kind '" + row.fields[2] + "', expected series or repeat");
        std::size_t g = 0;
        while (g < r.gauges.size() && r.gauges[g].name != name)
            ++g;
        if (g == r.gauges.size()) {
            if (repeat)
                throw file.error(row, "gauge " + name + "'s repeat before its series");
            r.gauges.push_back(LevelGauge{name, file.number(row, 1), {}, {}});
            r.series.emplace_back();
            r.repeat.emplace_back();
        } else if (file.number(row, 1) != r.gauges[g].x) {
            throw file.error(row, "gauge " + name + " at another x");
        }
        auto& points = repeat ? r.repeat[g] : r.series[g];
        const LevelPoint p{file.number(row, 3) / kSqrtGOverH, file.number(row, 4) * kColumnHeight};
        if (!points.empty() && p.t <= points.back().t)
            throw file.error(row, "time not after the previous row's");
        points.push_back(p);
    }
    for (std::size_t g = 0; g < r.gauges.size(); ++g) {
        if (!r.repeat[g].empty() && r.repeat[g].size() != r.series[g].size())
            throw RecordFileError(file.path.string() + ": gauge " + r.gauges[g].name +
                                  "'s repeat has another number of rows than its series");
        r.gauges[g].series = r.series[g];
        r.gauges[g].repeat = r.repeat[g];
    }
    return r;
}

} // namespace

LobovskyGeometry lobovskyH300Geometry() {
    // tankLength, columnLength, columnHeight: TNL-SPH examples/WCSPH-DBC/damBreak2D_WCSPH-DBC/
    // init.py defaults (--box-length 1.61, --fluid-length 0.6, --fluid-height 0.3). TNL-SPH uses
    // a 0.8 m box height of its own; 0.6 m is the paper's tank height as recalled (unverified).
    return LobovskyGeometry{1.61, 0.6, 0.6, kColumnHeight};
}

std::span<const LevelGauge> lobovskyH300Gauges() {
    static const LobovskyRecords records = loadRecords();
    return records.gauges;
}

} // namespace swell::bake::validation
