#include "ensemble_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using nlohmann::json;

namespace swell::bake {
namespace {

/// A member's figure for the ensemble's spread: NaN for null, which stays out of the spread.
double numberOrNaN(const json& v) {
    return v.is_null() ? std::nan("") : v.get<double>();
}

} // namespace

Figures regularWaveFigures(const json& r) {
    const std::vector<double> e = r["height_errors"].get<std::vector<double>>();
    double worst = 0.0;
    for (double x : e)
        worst = std::max(worst, std::abs(x));
    // Each standard error's mean over the members is what one record predicts for the
    // members' spread of the figure above it.
    return {{"height_error_first_gauge", e.front()},
            {"height_error_first_gauge_standard_error",
             numberOrNaN(r["height_errors_standard_error"].front())},
            {"height_error_worst_gauge", worst},
            {"decay_total", r["decay_total"].get<double>()},
            {"decay_total_fit", r["decay_total_fit"].get<double>()},
            {"decay_total_fit_standard_error", numberOrNaN(r["decay_total_fit_standard_error"])},
            {"wavelength_fit_error", r["wavelength_fit_error"].get<double>()}};
}

Figures lobovskyFigures(const json& r) {
    Figures f;
    for (const json& g : r["gauges"]) {
        const std::string name = g["name"].get<std::string>();
        f.push_back({"mean_abs_error_over_H_" + name, g["mean_abs_error_over_H"].get<double>()});
        f.push_back(
            {"mean_signed_error_over_H_" + name, g["mean_signed_error_over_H"].get<double>()});
        // The same for every member; kept beside the errors it bounds (NaN: no second series).
        f.push_back(
            {"experiment_scatter_over_H_" + name, numberOrNaN(g["experiment_scatter_over_H"])});
    }
    f.push_back({"mean_abs_error_over_H_worst", r["mean_abs_error_over_H_worst"].get<double>()});
    for (const json& g : r["gauges"]) {
        f.push_back({"mean_abs_error_over_H_run_up_" + g["name"].get<std::string>(),
                     g["mean_abs_error_over_H_run_up"].get<double>()});
    }
    f.push_back({"mean_abs_error_over_H_worst_run_up",
                 r["mean_abs_error_over_H_worst_run_up"].get<double>()});
    f.push_back({"far_gauge_landing_time", numberOrNaN(r["far_gauge_landing_time"])});
    const json& p1 = r["far_wall_pressure"];
    // NaN for a figure that says nothing, and for all of them without a sensor.
    const auto value = [&p1](const char* record, const char* key) {
        if (p1.is_null())
            return std::nan("");
        return numberOrNaN(record ? p1[record][key] : p1[key]);
    };
    f.push_back({"far_wall_impact_time", value(nullptr, "impact_time")});
    f.push_back({"far_wall_second_peak_time", value(nullptr, "second_peak_time")});
    f.push_back({"far_wall_second_peak", value(nullptr, "second_peak")});
    f.push_back(
        {"far_wall_mean_abs_error_delta_sph_320", value("delta_sph_320", "mean_abs_error")});
    f.push_back({"far_wall_mean_abs_error_experiment", value("experiment", "mean_abs_error")});
    return f;
}

Figures stillTankFigures(const json& r) {
    return {{"bottom_pressure_ratio", r["bottom_pressure_ratio"].get<double>()},
            {"max_speed_over_sqrt_gH", r["max_speed_over_sqrt_gH"].get<double>()},
            {"max_speed_before_shift_over_sqrt_gH",
             r["max_speed_before_shift_over_sqrt_gH"].get<double>()},
            {"max_drift_speed_over_sqrt_gH", r["max_drift_speed_over_sqrt_gH"].get<double>()},
            {"mean_speed_over_sqrt_gH", r["mean_speed_over_sqrt_gH"].get<double>()},
            {"max_excursion_over_l0", r["max_excursion_over_l0"].get<double>()}};
}

Figures standingWaveFigures(const json& r) {
    return {{"period_error", r["period_error"].get<double>()},
            {"decay_per_period", r["decay_per_period"].get<double>()},
            {"first_amplitude_over_theory", r["first_amplitude_over_theory"].get<double>()}};
}

Figures solitaryWaveFigures(const json& r) {
    return {{"celerity_error", r["celerity_error"].get<double>()},
            {"first_amplitude_over_height", r["first_amplitude_over_height"].get<double>()},
            {"decay_total", r["decay_total"].get<double>()},
            {"mean_width_error", r["mean_width_error"].get<double>()}};
}

Figures wetDamBreakFigures(const json& r) {
    return {{"bore_speed_error", r["bore_speed_error"].get<double>()},
            {"plateau_depth_error", numberOrNaN(r["plateau_depth_error"])},
            {"mean_abs_error_over_h0_worst", r["mean_abs_error_over_h0_worst"].get<double>()}};
}

Figures shoalingFigures(const json& r) {
    Figures f{{"incident_crest_error", r["incident_crest_error"].get<double>()},
              {"crest_error_worst", r["crest_error_worst"].get<double>()},
              {"amplification_error_worst", r["amplification_error_worst"].get<double>()},
              {"mean_abs_error_over_h0_worst", r["mean_abs_error_over_h0_worst"].get<double>()},
              {"travel_time_error", r["travel_time_error"].get<double>()}};
    for (const json& g : r["gauge_records"]) {
        const std::string name = g["name"].get<std::string>();
        f.push_back({"crest_over_h0_" + name, g["crest_over_h0"].get<double>()});
        f.push_back({"mean_abs_error_over_h0_" + name, g["mean_abs_error_over_h0"].get<double>()});
        f.push_back({"energy_ratio_" + name, g["energy_ratio"].get<double>()});
        // A side whose half-height crossing the record's span does not hold reads null (NaN).
        for (const char* side : {"rise", "fall"})
            f.push_back({std::string(side) + "_" + name,
                         g[side].is_number() ? g[side].get<double>()
                                             : std::numeric_limits<double>::quiet_NaN()});
    }
    return f;
}

Figures damBreakFigures(const json& r) {
    return {{"front_error_mean", r["front_error_mean"].get<double>()},
            {"aligned_front_error_mean", r["aligned_front_error_mean"].get<double>()},
            {"aligned_front_error_max", r["aligned_front_error_max"].get<double>()}};
}

} // namespace swell::bake
