#include "swell/bake/validation/martin_moyce1952.h"

#include <array>
#include <string_view>
#include <vector>

#include "swell/bake/validation/record_file.h"

namespace swell::bake::validation {
namespace {

/// The two series of the figure, in the file's order.
struct MartinMoyceRecords {
    std::vector<FrontPoint> a225, a1125;
};

MartinMoyceRecords loadRecords() {
    static constexpr std::array<std::string_view, 3> kColumns{"series", "T", "Z"};
    const RecordFile file = readValidationRecords(kMartinMoyceFile, kColumns);
    MartinMoyceRecords r;
    for (const RecordRow& row : file.rows) {
        std::vector<FrontPoint>* series = row.fields[0] == "a2.25in"    ? &r.a225
                                          : row.fields[0] == "a1.125in" ? &r.a1125
                                                                        : nullptr;
        if (!series)
            throw file.error(row, "series '" + row.fields[0] + "', expected a2.25in or a1.125in");
        const FrontPoint p{file.number(row, 1), file.number(row, 2)};
        if (!series->empty() && p.T <= series->back().T)
            throw file.error(row, "T not after the previous row's");
        series->push_back(p);
    }
    if (r.a225.empty() || r.a1125.empty())
        throw RecordFileError(file.path.string() + ": a series without rows");
    return r;
}

const MartinMoyceRecords& records() {
    static const MartinMoyceRecords r = loadRecords();
    return r;
}

} // namespace

std::span<const FrontPoint> martinMoyceA225() {
    return records().a225;
}

std::span<const FrontPoint> martinMoyceA1125() {
    return records().a1125;
}

} // namespace swell::bake::validation
