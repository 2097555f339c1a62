// libFuzzer target for scene files (docs/scenes.md): any byte string is a scene file. It must
// either load (then every property below holds) or be refused with one SceneError line naming
// a key; nothing else may escape, crash, hang or allocate without bound. The solver never runs;
// the particle geometry is generated (parseScene does) and, for small scenes, the solver built.
#include "fuzz_check.h"

#include "swell/bake/bake_driver.h"
#include "swell/bake/error.h"
#include "swell/bake/scene.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

using namespace swell::bake;
using swell::fuzz::require;

namespace {

void checkAccepted(const Scene& scene) {
    // Round trip: the resolved scene is a scene, and the same one.
    const nlohmann::json resolved = toJson(scene);
    Scene again;
    try {
        again = parseScene(resolved);
    } catch (const SceneError& e) {
        swell::fuzz::fail("an accepted scene's resolved JSON is refused", e.what());
    }
    require(toJson(again) == resolved, "the resolved scene does not round-trip", resolved.dump());
    require(std::isfinite(scene.solver.time.dt) && scene.solver.time.dt > 0.0, "dt not positive");
    require(std::isfinite(scene.run.endTime) && scene.run.endTime > 0.0, "end_time not positive");
    // What swell-bake checks before it bakes: refused with a SceneError or usable.
    try {
        require(frameIntervalSteps(scene) >= 1, "frame interval below one step");
        require(totalSteps(scene) >= 1, "no step to run");
        (void)sceneWarnings(scene);
    } catch (const SceneError& e) {
        swell::fuzz::requireClearError(e.what(), e.key().empty() ? "" : "scene key '");
    }
    const GeneratedGeometry geo = generateGeometry(scene.geometry);
    require(geo.particles.size() <= kMaxParticles, "more particles than kMaxParticles");
    const Box& d = geo.domain;
    for (std::size_t i = 0; i < geo.particles.size(); ++i) {
        const double x = geo.particles.x[i], y = geo.particles.y[i];
        require(std::isfinite(x) && std::isfinite(y) && x > d.x0 && x < d.x1 && y > d.y0 &&
                    y < d.y1,
                "a generated particle lies outside the domain");
    }
    if (geo.particles.size() <= 20000)
        (void)makeSolver(scene);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Scene scene;
    try {
        // As loadScene reads a file (parseSceneJson), from memory.
        scene = parseScene(parseSceneJson(
            std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json"));
    } catch (const SceneError& e) {
        swell::fuzz::requireClearError(e.what(), e.key().empty() ? "" : "scene key '");
        return 0;
    }
    checkAccepted(scene);
    return 0;
}
