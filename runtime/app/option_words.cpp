#include "option_words.h"

#include <string_view>
#include <utility>

namespace swell::play {

namespace {

/// Each parameter name an error may start with, and the option as --help lists it. Longer
/// names before the shorter names they begin with.
constexpr std::pair<std::string_view, std::string_view> kOptionOf[] = {
    {"cells_x x cells_z", "--res"},
    {"policy", "--policy"},
    {"reconstruction", "--reconstruction"},
    {"time_sampling", "--time-sampling"},
    {"noise.filter", "--filter"},
    {"slices", "--slices"},
    {"fluctuation", "-F/--fluctuation"},
    {"time_unit_seconds", "--time-unit"},
    {"sigma", "--sigma"},
    {"extent_x", "--extent"},
    {"crossfade_seconds", "--crossfade"},
    {"noise.time_samples", "--noise-time"},
    {"noise.beta", "--beta"},
    {"noise.cutoff", "--cutoff"},
    {"ripple.angles", "--angles"},
    {"ripple.weights", "--weights"},
    {"whirlpool.inner_radius_cells", "--spiral-a"},
    {"whirlpool.growth", "--spiral-b"},
    {"whirlpool.turns_per_time_unit", "--spin"},
    {"whirlpool.eye_depth", "--eye-depth"},
    {"image size", "--size"},
    {"samples", "--samples"},
    {"camera fov", "--fov"},
    {"camera position and target", "--camera/--target"},
    {"camera looks", "--camera/--target: the camera looks"},
    {"sky sun elevation", "--sun-elevation"},
    {"sky sun azimuth", "--sun-azimuth"},
    {"splash count (artificial per real)", "--splash-count"},
    {"splash spawn radius", "--splash-spread"},
    {"splash sprite radius", "--splash-radius"},
};

} // namespace

std::string inOptionWords(const std::string& message) {
    for (const auto& [name, option] : kOptionOf) {
        if (message.size() > name.size() && message.compare(0, name.size(), name) == 0 &&
            (message[name.size()] == ' ' || message[name.size()] == ':'))
            return std::string(option) + message.substr(name.size());
    }
    return message;
}

} // namespace swell::play
