#include "ensemble.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>

#include "swell/bake/solver_run.h"
#include "swell/bake/validation/validation.h"

using namespace swell::bake::validation;
using nlohmann::json;

namespace swell::bake {
namespace {

json toJson(const Spread& s) {
    return {{"mean", s.mean}, {"sd", s.sd}, {"min", s.min}, {"max", s.max}, {"members", s.count}};
}

} // namespace

json ensemble(Scene scene, int n, const std::function<json(const Scene&)>& run,
              const std::function<Figures(const json&)>& figures) {
    if (!(scene.geometry.jitter > 0.0))
        scene.geometry.jitter = 1e-6;
    json members = json::array();
    std::vector<std::pair<std::string, std::vector<double>>> values;
    bool stable = true;
    for (int m = 1; m <= n; ++m) {
        scene.seed = static_cast<std::uint64_t>(m);
        json r = run(scene);
        r["seed"] = m;
        if (r["outcome"] != kStable) {
            stable = false;
        } else {
            const Figures f = figures(r);
            if (values.empty()) {
                for (const auto& [name, v] : f)
                    values.push_back({name, {}});
            }
            // A figure a member could not measure (NaN) stays out of the others' spread.
            for (std::size_t k = 0; k < f.size(); ++k) {
                if (std::isfinite(f[k].second))
                    values[k].second.push_back(f[k].second);
            }
        }
        std::fprintf(stderr, "swell-validate: ensemble member %d of %d: %s\n", m, n,
                     r["outcome"].get<std::string>().c_str());
        members.push_back(std::move(r));
    }
    json out{{"scene", scene.name},
             {"ensemble", n},
             {"jitter", scene.geometry.jitter},
             {"outcome", stable ? kStable : "stopped: a member stopped (see members)"},
             {"members", members}};
    // A figure no member measured reads null: an ensemble's other figures are never lost.
    for (const auto& [name, v] : values)
        out[name] = v.empty() ? json(nullptr) : toJson(spreadOf(v));
    return out;
}

} // namespace swell::bake
