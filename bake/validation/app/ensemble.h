#pragma once
// swell-validate --ensemble: a check run as members that differ only in their seed, and the
// spread of their figures.

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "swell/bake/scene.h"

namespace swell::bake {

/// Named figures of one member's report, whose spread over the ensemble is reported.
using Figures = std::vector<std::pair<std::string, double>>;

/// A check as an ensemble: members with seeds 1..n and the water jittered (by the scene's
/// geometry.jitter, or 1e-6 l0), the same flow up to a perturbation far below the resolution.
/// Where the flow amplifies small differences (a breaking jet, a wave train over several
/// wavelengths) one record is one draw, and the spread of the members' figures is how far it can be
/// trusted. `run` runs one member; `figures` reads the figures of a stable member's report, the
/// same names in the same order for every member.
nlohmann::json ensemble(Scene scene, int n, const std::function<nlohmann::json(const Scene&)>& run,
                        const std::function<Figures(const nlohmann::json&)>& figures);

} // namespace swell::bake
