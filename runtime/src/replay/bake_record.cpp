#include "swell/runtime/replay/bake_record.h"

#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace swell::runtime {
namespace {

using json = nlohmann::json;

double number(const json& block, const char* key) {
    if (!block.contains(key) || !block.at(key).is_number()) {
        throw std::invalid_argument(
            fmt::format("cache metadata replay.{}: missing or not a number", key));
    }
    const double v = block.at(key).get<double>();
    if (!std::isfinite(v))
        throw std::invalid_argument(fmt::format("cache metadata replay.{}: not finite", key));
    return v;
}

} // namespace

BakeRecord bakeRecord(const cache::Header& header) {
    BakeRecord r;
    r.waterXMin = header.domain.xMin;
    r.waterXMax = header.domain.xMax;
    r.stillWaterLevel = std::numeric_limits<double>::quiet_NaN();
    json meta;
    try {
        meta = json::parse(header.metadataJson);
    } catch (const json::exception&) {
        meta = json::object(); // the cache reader accepts any text; nothing is recorded then
    }
    if (!meta.is_object())
        meta = json::object();
    if (meta.contains("still_water_level") && meta["still_water_level"].is_number())
        r.stillWaterLevel = meta["still_water_level"].get<double>();
    const json* spacing = nullptr;
    if (meta.contains("scene") && meta["scene"].is_object() && meta["scene"].contains("geometry") &&
        meta["scene"]["geometry"].is_object() &&
        meta["scene"]["geometry"].contains("particle_spacing")) {
        spacing = &meta["scene"]["geometry"]["particle_spacing"];
    }
    if (spacing != nullptr && spacing->is_number())
        r.particleSpacing = spacing->get<double>();
    r.waveMakerXMax = std::numeric_limits<double>::quiet_NaN();
    if (meta.contains("scene") && meta["scene"].is_object() &&
        meta["scene"].contains("recycling") && meta["scene"]["recycling"].is_object()) {
        const json& rec = meta["scene"]["recycling"];
        if (rec.contains("inflow_x1") && rec["inflow_x1"].is_number() &&
            std::isfinite(rec["inflow_x1"].get<double>()))
            r.waveMakerXMax = rec["inflow_x1"].get<double>();
    }
    r.floorLevel = header.domain.yMin;
    const json* tank = nullptr;
    if (meta.contains("scene") && meta["scene"].is_object() && meta["scene"].contains("geometry") &&
        meta["scene"]["geometry"].is_object() && meta["scene"]["geometry"].contains("tank"))
        tank = &meta["scene"]["geometry"]["tank"];
    if (tank != nullptr && tank->is_object() && tank->contains("y0") && (*tank)["y0"].is_number() &&
        std::isfinite((*tank)["y0"].get<double>()))
        r.floorLevel = (*tank)["y0"].get<double>();

    if (!meta.contains("replay")) {
        r.note = "the cache records no water extent or steady start (baked before they were "
                 "recorded): the grid spans the cache domain and every frame is replayed; bake "
                 "again for both";
        r.steadyReason = "not recorded";
        return r;
    }
    const json& block = meta.at("replay");
    if (!block.is_object())
        throw std::invalid_argument("cache metadata replay: expected a JSON object");
    r.recorded = true;
    r.waterXMin = number(block, "water_x_min");
    r.waterXMax = number(block, "water_x_max");
    if (!(r.waterXMax > r.waterXMin)) {
        throw std::invalid_argument(
            fmt::format("cache metadata replay.water_x_max = {} is not above water_x_min = {}",
                        r.waterXMax, r.waterXMin));
    }
    r.stillWaterLevel = number(block, "still_water_level");
    r.particleSpacing = number(block, "particle_spacing");
    if (!(r.particleSpacing > 0.0)) {
        throw std::invalid_argument(fmt::format(
            "cache metadata replay.particle_spacing = {} must be > 0", r.particleSpacing));
    }
    r.steadyStartSeconds = number(block, "steady_start_s");
    if (r.steadyStartSeconds < 0.0) {
        throw std::invalid_argument(fmt::format(
            "cache metadata replay.steady_start_s = {} must be >= 0", r.steadyStartSeconds));
    }
    if (block.contains("steady_reason") && block["steady_reason"].is_string())
        r.steadyReason = block["steady_reason"].get<std::string>();
    return r;
}

std::pair<double, double> shownWaterX(const BakeRecord& record) {
    double x0 = record.waterXMin;
    if (std::isfinite(record.waveMakerXMax) && record.waveMakerXMax > x0 &&
        record.waveMakerXMax < record.waterXMax)
        x0 = record.waveMakerXMax;
    return {x0, record.waterXMax};
}

} // namespace swell::runtime
