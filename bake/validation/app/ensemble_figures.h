#pragma once
// The figures of each check whose spread an ensemble reports (ensemble.h), read from a stable
// member's report by name, the same names in the same order for every member.

#include <nlohmann/json.hpp>

#include "ensemble.h"

namespace swell::bake {

// One per check of case_reports.h, of the report it returns.
Figures damBreakFigures(const nlohmann::json& r);
Figures lobovskyFigures(const nlohmann::json& r);
Figures stillTankFigures(const nlohmann::json& r);
Figures regularWaveFigures(const nlohmann::json& r);
Figures standingWaveFigures(const nlohmann::json& r);
Figures solitaryWaveFigures(const nlohmann::json& r);
Figures wetDamBreakFigures(const nlohmann::json& r);
Figures shoalingFigures(const nlohmann::json& r);

} // namespace swell::bake
