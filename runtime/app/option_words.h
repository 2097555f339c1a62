#pragma once
// The replay's and the renderer's parameters are named in their errors by the keys of
// params_json (replay_params.h, mode_params.h) or by their plain names ("camera fov"); on
// swell-play's command line the user typed an option. This turns the one into the other.

#include <string>

namespace swell::play {

/// `message` with a leading parameter name replaced by the swell-play option that sets it
/// ("time_unit_seconds must be > 0, got 0" -> "--time-unit must be > 0, got 0"); unchanged
/// when it starts with no such name.
std::string inOptionWords(const std::string& message);

} // namespace swell::play
