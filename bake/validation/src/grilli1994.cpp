#include "swell/bake/validation/grilli1994.h"

#include <array>
#include <string_view>
#include <vector>

#include "swell/bake/validation/record_file.h"

namespace swell::bake::validation {
namespace {

/// The gauges and the storage their spans point into.
struct GrilliRecords {
    std::vector<std::vector<ShoalingSample>> samples;
    std::vector<ShoalingGauge> gauges;
};

GrilliRecords loadRecords() {
    static constexpr std::array<std::string_view, 4> kColumns{"gauge", "x", "t", "eta"};
    const RecordFile file = readValidationRecords(kGrilli1994File, kColumns);
    GrilliRecords r;
    for (const RecordRow& row : file.rows) {
        const std::string& name = row.fields[0];
        if (r.gauges.empty() || r.gauges.back().name != name) {
            for (const ShoalingGauge& g : r.gauges)
                if (g.name == name)
                    throw file.error(row, "gauge " + name + "'s rows are not contiguous");
            r.gauges.push_back(ShoalingGauge{name, file.number(row, 1), {}});
            r.samples.emplace_back();
        } else if (file.number(row, 1) != r.gauges.back().xOverDepth) {
            throw file.error(row, "gauge " + name + " at another x");
        }
        const ShoalingSample s{file.number(row, 2), file.number(row, 3)};
        if (!r.samples.back().empty() && s.t <= r.samples.back().back().t)
            throw file.error(row, "time not after the previous row's");
        r.samples.back().push_back(s);
    }
    for (std::size_t g = 0; g < r.gauges.size(); ++g)
        r.gauges[g].record = r.samples[g];
    return r;
}

} // namespace

std::span<const ShoalingGauge> grilli1994Gauges() {
    static const GrilliRecords records = loadRecords();
    return records.gauges;
}

} // namespace swell::bake::validation
