#include "swell/bake/validation/buchner2002.h"

#include <array>
#include <string_view>
#include <vector>

#include "swell/bake/validation/record_file.h"

namespace swell::bake::validation {
namespace {

std::vector<FarWallPressureSample> loadRecords() {
    static constexpr std::array<std::string_view, 5> kColumns{"t", "experiment", "delta_sph_40",
                                                              "delta_sph_80", "delta_sph_320"};
    const RecordFile file = readValidationRecords(kBuchnerP1File, kColumns);
    std::vector<FarWallPressureSample> rows;
    for (const RecordRow& row : file.rows) {
        const FarWallPressureSample s{file.number(row, 0), file.number(row, 1), file.number(row, 2),
                                      file.number(row, 3), file.number(row, 4)};
        if (!rows.empty() && s.t <= rows.back().t)
            throw file.error(row, "time not after the previous row's");
        rows.push_back(s);
    }
    return rows;
}

} // namespace

std::span<const FarWallPressureSample> buchnerP1Records() {
    static const std::vector<FarWallPressureSample> records = loadRecords();
    return records;
}

} // namespace swell::bake::validation
