#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "swell/bake/error.h"
#include "swell/bake/scene.h"
#include "temp_dir.h"

using namespace swell::bake;
using nlohmann::json;

namespace {

const std::filesystem::path kScenes = SWELL_SCENES_DIR;

json minimal() {
    return json::parse(R"({
        "geometry": {
            "particle_spacing": 0.01,
            "tank": {"x0": 0, "y0": 0, "x1": 0.5, "y1": 0.3},
            "water": [{"x0": 0, "y0": 0, "x1": 0.1, "y1": 0.2}]
        },
        "solver": {"dt": 0.001}
    })");
}

/// The key named by the SceneError that parsing `j` throws.
std::string errorKey(const json& j) {
    try {
        parseScene(j);
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find(e.key()), std::string::npos)
            << "message must name the key";
        return e.key();
    }
    return "<accepted>";
}

/// Each of `bad` as solver.<key> of the minimal scene is a SceneError naming solver.<key>.
void expectSolverKeyRejects(const std::string& key, std::initializer_list<json> bad) {
    for (const json& value : bad) {
        json j = minimal();
        j["solver"][key] = value;
        EXPECT_EQ(errorKey(j), "solver." + key) << value;
    }
}

/// The message of the SceneError that parsing `j` throws, "<accepted>" when it throws none.
std::string errorMessage(const json& j) {
    try {
        parseScene(j);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "<accepted>";
}

} // namespace

TEST(Scene, ShippedScenesLoad) {
    for (const char* name :
         {"still_tank.json", "still_tank_small.json", "dam_break.json", "dam_break_small.json",
          "standing_wave.json", "standing_wave_small.json", "solitary_wave.json",
          "solitary_wave_small.json"}) {
        SCOPED_TRACE(name);
        const Scene s = loadScene(kScenes / name);
        EXPECT_FALSE(s.name.empty());
        EXPECT_FALSE(s.geometry.water.empty());
        EXPECT_TRUE(s.geometry.tank.has_value());
    }
}

TEST(Scene, DamBreakSceneIsTheMartinMoyceSetUp) {
    for (const char* name : {"dam_break.json", "dam_break_small.json"}) {
        const Scene s = loadScene(kScenes / name);
        const Box col = s.geometry.water.at(0);
        const Box tank = *s.geometry.tank;
        EXPECT_DOUBLE_EQ(col.x0, 0.0); // back wall inner face at x = 0
        EXPECT_DOUBLE_EQ(col.y0, 0.0); // bed at y = 0
        EXPECT_DOUBLE_EQ(tank.x0, 0.0);
        EXPECT_DOUBLE_EQ(tank.y0, 0.0);
        EXPECT_NEAR(col.height(), 2.0 * col.width(), 1e-12); // height 2a
        EXPECT_GE(tank.width(), 5.0 * col.width() - 1e-12);  // tank at least 5a long
    }
}

TEST(Scene, DefaultsFillMissingSectionsAndKeys) {
    const Scene s = parseScene(minimal());
    EXPECT_DOUBLE_EQ(s.solver.model.reDensity, 2.8); // the swell scheme's
    EXPECT_DOUBLE_EQ(s.solver.model.reLaplacian, 3.1);
    EXPECT_DOUBLE_EQ(s.physics.density, 1000.0);
    EXPECT_EQ(s.geometry.wallLayers, 2);
    EXPECT_DOUBLE_EQ(s.output.splashRatio, 0.49);
    EXPECT_DOUBLE_EQ(s.output.surfaceRatio, 0.96);
}

TEST(Scene, EnumsAreReadByName) {
    json j = minimal();
    j["solver"]["preconditioner"] = "jacobi";
    j["solver"]["source_term"] = "mixed";
    const Scene s = parseScene(j);
    EXPECT_EQ(s.solver.pressure.preconditioner, Preconditioner::Jacobi);
    EXPECT_EQ(s.solver.pressure.sourceTerm, SourceTerm::Mixed);
    j["solver"]["preconditioner"] = "multigrid";
    EXPECT_EQ(errorKey(j), "solver.preconditioner");
    j["solver"]["preconditioner"] = 1;
    EXPECT_EQ(errorKey(j), "solver.preconditioner");
}

TEST(Scene, UnknownKeysAreRejectedNamingTheKey) {
    json j = minimal();
    j["solver"]["dtt"] = 0.001;
    EXPECT_EQ(errorKey(j), "solver.dtt");
    j = minimal();
    j["physic"] = json::object();
    EXPECT_EQ(errorKey(j), "physic");
    j = minimal();
    j["geometry"]["water"][0]["z0"] = 0.0;
    EXPECT_EQ(errorKey(j), "geometry.water[0].z0");
}

TEST(Scene, WrongTypesAreRejectedNamingTheKey) {
    json j = minimal();
    j["solver"]["dt"] = "0.001";
    EXPECT_EQ(errorKey(j), "solver.dt");
    j = minimal();
    j["solver"]["adaptive_dt"] = 1;
    EXPECT_EQ(errorKey(j), "solver.adaptive_dt");
    j = minimal();
    j["geometry"]["wall_layers"] = 2.5;
    EXPECT_EQ(errorKey(j), "geometry.wall_layers");
    j = minimal();
    j["geometry"]["water"] = json::object();
    EXPECT_EQ(errorKey(j), "geometry.water");
    j = minimal();
    j["physics"] = 3;
    EXPECT_EQ(errorKey(j), "physics");
}

TEST(Scene, BadValuesAreRejectedNamingTheKey) {
    json j = minimal();
    j["geometry"]["particle_spacing"] = -0.01;
    EXPECT_EQ(errorKey(j), "geometry.particle_spacing");
    j = minimal();
    j["geometry"]["water"] = json::array();
    EXPECT_EQ(errorKey(j), "geometry.water");
    j = minimal();
    j["geometry"]["water"][0]["x1"] = 0.0; // empty fluid region
    EXPECT_EQ(errorKey(j), "geometry.water[0]");
    j = minimal();
    j["geometry"]["water"][0]["x1"] = 0.005; // holds no particle
    EXPECT_EQ(errorKey(j), "geometry.water[0]");
    j = minimal();
    j["solver"]["surface_threshold"] = 1.5;
    EXPECT_EQ(errorKey(j), "solver.surface_threshold");
    j = minimal();
    j["output"]["splash_ratio"] = 0.97;
    EXPECT_EQ(errorKey(j), "output.splash_ratio");
    j = minimal();
    j["geometry"]["jitter"] = 0.2; // more than 0.1 l0
    EXPECT_EQ(errorKey(j), "geometry.jitter");
    j = minimal();
    j["solver"]["substep_courant"] = -0.1;
    EXPECT_EQ(errorKey(j), "solver.substep_courant");
    j = minimal();
    j["solver"]["substep_courant"] = 1.5;
    EXPECT_EQ(errorKey(j), "solver.substep_courant");
    j = minimal();
    j.erase("geometry");
    EXPECT_EQ(errorKey(j), "geometry");
}

TEST(Scene, TimeStepAboveTheCourantLimitIsRejected) {
    // Expected speed 2 sqrt(g H) = 2 sqrt(9.81 x 0.2) = 2.80 m/s; l0 = 0.01 m; limit 0.8
    // (the default): dt may be at most 0.8 x 0.01 / 2.80 = 2.86 ms.
    json j = minimal();
    j["solver"]["dt"] = 0.0028;
    EXPECT_EQ(errorKey(j), "<accepted>");
    j["solver"]["dt"] = 0.0029;
    EXPECT_EQ(errorKey(j), "solver.dt");
    j["solver"]["courant_limit"] = 0.9; // a looser detector accepts it
    EXPECT_EQ(errorKey(j), "<accepted>");
    j["solver"]["courant_limit"] = 0.5; // a stricter one rejects a step it accepted
    j["solver"]["dt"] = 0.0019;
    EXPECT_EQ(errorKey(j), "solver.dt");
    j["solver"].erase("courant_limit");
    j["solver"]["dt"] = 0.0029;
    EXPECT_EQ(errorKey(j), "solver.dt");
    j["solver"]["expected_speed"] = 1.0; // the scene says it is slower
    EXPECT_EQ(errorKey(j), "<accepted>");
    j["solver"]["expected_speed"] = 0.0;
    j["solver"]["adaptive_dt"] = true; // dt is then only the largest step
    EXPECT_EQ(errorKey(j), "<accepted>");
}

TEST(Scene, ToJsonRoundTrips) {
    json j = minimal();
    j["solver"]["preconditioner"] = "incomplete_cholesky";
    j["solver"]["gradient_correction"] = true;
    j["geometry"]["solids"] = json::array({{{"x0", 0.3}, {"y0", 0.0}, {"x1", 0.35}, {"y1", 0.05}}});
    const Scene a = parseScene(j);
    const Scene b = parseScene(toJson(a));
    EXPECT_EQ(toJson(a), toJson(b));
    EXPECT_EQ(b.solver.pressure.preconditioner, Preconditioner::IncompleteCholesky);
    EXPECT_TRUE(usesCorrectiveMatrix(b.solver.model.gradient));
    ASSERT_EQ(b.geometry.solids.size(), 1u);
}

TEST(Scene, WaterSurfaceIsReadRoundTripsAndNamesItsKeys) {
    json j = minimal();
    j["geometry"]["water"][0]["surface"] = {{"amplitude", 0.02}, {"wavelength", 0.2}};
    const Scene a = parseScene(j);
    ASSERT_EQ(a.geometry.waterTops.size(), 1u);
    EXPECT_EQ(a.geometry.waterTops[0].amplitude, 0.02);
    EXPECT_EQ(a.geometry.waterTops[0].wavelength, 0.2);
    EXPECT_EQ(toJson(parseScene(toJson(a))), toJson(a));
    EXPECT_EQ(toJson(a)["geometry"]["water"][0]["surface"]["wavelength"], 0.2);
    // A flat top writes no surface: scenes without one keep their recorded form.
    EXPECT_FALSE(toJson(parseScene(minimal()))["geometry"]["water"][0].contains("surface"));

    j["geometry"]["water"][0]["surface"]["phase"] = 0.5;
    EXPECT_EQ(errorKey(j), "geometry.water[0].surface.phase");
    j["geometry"]["water"][0]["surface"] = {{"amplitude", "big"}, {"wavelength", 0.2}};
    EXPECT_EQ(errorKey(j), "geometry.water[0].surface.amplitude");
    j["geometry"]["water"][0]["surface"] = {{"amplitude", 0.02}, {"wavelength", -1.0}};
    EXPECT_EQ(errorKey(j), "geometry.water[0].surface.wavelength");
    j["geometry"]["water"][0]["surface"] = 0.02;
    EXPECT_EQ(errorKey(j), "geometry.water[0].surface");
}

TEST(Scene, OverridesSetNestedKeysWithJsonValues) {
    json j = minimal();
    applyOverride(j, "solver.dt=0.0005");
    applyOverride(j, "solver.preconditioner=jacobi"); // not JSON: taken as a string
    applyOverride(j, "output.frame_interval=0.1");    // creates the section
    const Scene s = parseScene(j);
    EXPECT_DOUBLE_EQ(s.solver.time.dt, 0.0005);
    EXPECT_EQ(s.solver.pressure.preconditioner, Preconditioner::Jacobi);
    EXPECT_DOUBLE_EQ(s.output.frameInterval, 0.1);
    EXPECT_THROW(applyOverride(j, "solver.dt"), SceneError);
    EXPECT_THROW(applyOverride(j, "solver.dt.x=1"), SceneError);
}

TEST(Scene, UnreadableFilesAreSceneErrors) {
    EXPECT_THROW(loadScene(kScenes / "no_such_scene.json"), SceneError);
    const swell::test::TempDir dir("swell_bad_scene_");
    const auto tmp = dir / "bad.json";
    {
        std::FILE* f = std::fopen(tmp.c_str(), "w");
        std::fputs("{ \"geometry\": ", f);
        std::fclose(f);
    }
    EXPECT_THROW(loadScene(tmp), SceneError);
}

namespace {

json withPiston() {
    json j = minimal();
    j["geometry"]["tank"] = json::parse(R"({"x0": 0, "y0": 0, "x1": 1.0, "y1": 0.3})");
    j["geometry"]["water"] = json::parse(R"([{"x0": 0, "y0": 0, "x1": 1.0, "y1": 0.1}])");
    j["piston"] = json::parse(R"({"kind": "sinusoidal", "period": 1.0, "stroke": 0.04})");
    j["output"] = json::parse(R"({"gauges": [0.3, 0.6]})");
    return j;
}

} // namespace

TEST(Scene, WaveScenesLoad) {
    for (const char* name : {"surging.json", "surging_small.json"}) {
        SCOPED_TRACE(name);
        const Scene s = loadScene(kScenes / name);
        ASSERT_TRUE(s.piston.has_value());
        EXPECT_EQ(s.piston->kind, PistonKind::Random);
        EXPECT_EQ(s.piston->seed, s.seed);
        EXPECT_FALSE(s.output.gauges.empty());
    }
    // The paper's scale (Table 2: 8,376 water + 1,662 fixed particles, 12K steps of 1 ms =
    // 12 s). The fixed particles up to 1 m are about 17 % more than the paper's (the breaking
    // waves' run-up must stay in the tank); the walls go on to 1.5 m for the spray, which
    // reaches up to 1.42 m (docs/validation.md 7.6).
    const Scene s = loadScene(kScenes / "surging.json");
    const GeneratedGeometry g = generateGeometry(s.geometry);
    const Particles& p = g.particles;
    const std::size_t water = p.count(ParticleKind::Water);
    std::size_t fixedBelow1m = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        fixedBelow1m += p.kind[i] != ParticleKind::Water && p.y[i] < 1.0 ? 1 : 0;
    EXPECT_NEAR(static_cast<double>(water), 8376.0, 0.05 * 8376.0);
    EXPECT_NEAR(static_cast<double>(fixedBelow1m), 1662.0, 0.2 * 1662.0);
    ASSERT_TRUE(s.geometry.tank.has_value());
    EXPECT_GE(s.geometry.tank->y1, 1.5);
    EXPECT_NEAR(s.run.endTime / s.solver.time.dt, 12000.0, 0.5);
}

TEST(Scene, PistonSeedGaugesRoundTrip) {
    json j = withPiston();
    j["seed"] = 42;
    j["output"]["still_water_level"] = 0.1;
    const Scene a = parseScene(j);
    EXPECT_EQ(a.seed, 42u);
    EXPECT_EQ(a.piston->seed, 42u);
    EXPECT_DOUBLE_EQ(a.geometry.bedExtensionBack, 0.02); // room for the sinusoid's S/2 backwards
    const Scene b = parseScene(toJson(a));
    EXPECT_EQ(toJson(a), toJson(b));
    EXPECT_EQ(b.output.gauges, (std::vector<double>{0.3, 0.6}));
    EXPECT_DOUBLE_EQ(stillWaterLevel(b), 0.1);
    EXPECT_EQ(toJson(b)["piston"]["kind"], "sinusoidal");
}

TEST(Scene, PistonAndGaugeErrorsNameTheKey) {
    json j = withPiston();
    j["piston"]["kind"] = "wobbly";
    EXPECT_EQ(errorKey(j), "piston.kind");
    j = withPiston();
    j["piston"]["strok"] = 0.1;
    EXPECT_EQ(errorKey(j), "piston.strok");
    j = withPiston();
    j["piston"]["period"] = 0;
    EXPECT_EQ(errorKey(j), "piston.period");
    j = withPiston();
    j["piston"] = json::parse(R"({"kind": "random", "period_min": 2.0, "period_max": 1.0})");
    EXPECT_EQ(errorKey(j), "piston.period_max");
    j = withPiston();
    j["piston"] = json::parse(R"({"kind": "random", "stroke_min": 0.2, "stroke_max": 0.1})");
    EXPECT_EQ(errorKey(j), "piston.stroke_max");
    j = withPiston();
    j["piston"]["stroke"] = 1.2; // travels 0.6 m in a 1 m tank
    EXPECT_EQ(errorKey(j), "piston.stroke");
    j = withPiston();
    j["piston"] = "yes";
    EXPECT_EQ(errorKey(j), "piston");
    j = withPiston();
    j["geometry"].erase("tank");
    EXPECT_EQ(errorKey(j), "piston");
    j = withPiston();
    j["output"]["gauges"] = json::parse("[0.3, 1.5]");
    EXPECT_EQ(errorKey(j), "output.gauges[1]");
    j = withPiston();
    j["output"]["gauges"] = json::parse(R"([0.3, "middle"])");
    EXPECT_EQ(errorKey(j), "output.gauges[1]");
    j = withPiston();
    j["output"]["gauges"] = 0.3;
    EXPECT_EQ(errorKey(j), "output.gauges");
    j = withPiston();
    j["seed"] = -1;
    EXPECT_EQ(errorKey(j), "seed");
    j = withPiston();
    j["seed"] = "one";
    EXPECT_EQ(errorKey(j), "seed");
    j = withPiston();
    j["output"]["still_water_level"] = "top";
    EXPECT_EQ(errorKey(j), "output.still_water_level");
    EXPECT_EQ(errorKey(withPiston()), "<accepted>");
}

TEST(Scene, SolitaryPistonTakesItsDepthFromTheWaterAndNamesItsKeys) {
    json j = withPiston();
    j["piston"] = json::parse(R"({"kind": "solitary", "height": 0.03})");
    const Scene a = parseScene(j);
    ASSERT_TRUE(a.piston.has_value());
    EXPECT_EQ(a.piston->kind, PistonKind::Solitary);
    EXPECT_DOUBLE_EQ(a.piston->depth, 0.1); // the still water over the tank's bed
    EXPECT_DOUBLE_EQ(a.piston->gravity, a.physics.gravity);
    EXPECT_DOUBLE_EQ(a.geometry.bedExtensionBack, 0.0); // it only moves forward
    EXPECT_EQ(toJson(a)["piston"]["height"], 0.03);
    EXPECT_EQ(toJson(parseScene(toJson(a))), toJson(a));
    // Other kinds serialize as before: no height.
    EXPECT_FALSE(toJson(parseScene(withPiston()))["piston"].contains("height"));

    j["piston"]["height"] = 0.08; // H / h = 0.8: above McCowan's 0.78, the wave breaks
    EXPECT_EQ(errorKey(j), "piston.height");
    j["piston"]["height"] = 0.0;
    EXPECT_EQ(errorKey(j), "piston.height");
    j["piston"]["height"] = 0.03;
    j["geometry"]["water"] = json::array();
    EXPECT_EQ(errorKey(j), "geometry.water"); // no water, no depth to make the wave for
    j = withPiston();
    j["piston"] = json::parse(R"({"kind": "solitary", "height": 0.03})");
    j["output"]["still_water_level"] = 0.0; // at the bed: no depth either
    EXPECT_EQ(errorKey(j), "piston.kind");
    // A stroke (sqrt(16 H h / 3) = 0.204 m for H = 0.078, h = 0.1) past half a 0.4 m tank.
    j = withPiston();
    j["geometry"]["tank"]["x1"] = 0.4;
    j["geometry"]["water"][0]["x1"] = 0.4;
    j["output"]["gauges"] = json::parse("[0.3]");
    j["piston"] = json::parse(R"({"kind": "solitary", "height": 0.078})");
    EXPECT_EQ(errorKey(j), "piston.height");
}

TEST(Scene, RippleScenesLoadAndRecyclingErrorsNameTheKey) {
    for (const char* name : {"ripple.json", "ripple_small.json"}) {
        SCOPED_TRACE(name);
        const Scene s = loadScene(kScenes / name);
        ASSERT_TRUE(s.recycling.has_value());
        EXPECT_EQ(toJson(parseScene(toJson(s))), toJson(s));
    }
    json j = withPiston();
    j.erase("piston");
    j["recycling"] = json::parse(R"({"inflow_x1": 0.2, "velocity": 0.2, "outflow_x": 0.8})");
    EXPECT_EQ(errorKey(j), "<accepted>");
    j["recycling"]["outflow_x"] = 1.0; // at the front wall: no room for the outflow
    EXPECT_EQ(errorKey(j), "recycling.outflow_x");
    j["recycling"]["outflow_x"] = 0.1; // upstream of the inflow zone's end
    EXPECT_EQ(errorKey(j), "recycling.outflow_x");
    j["recycling"]["outflow_x"] = 0.8;
    j["recycling"]["inflow_x1"] = 0.0;
    EXPECT_EQ(errorKey(j), "recycling.inflow_x1");
    j["recycling"]["inflow_x1"] = 0.2;
    j["recycling"]["speed"] = 1.0;
    EXPECT_EQ(errorKey(j), "recycling.speed");
    j["recycling"].erase("speed");
    j["piston"] = json::object();
    EXPECT_EQ(errorKey(j), "recycling");
}

TEST(Scene, RecordedConstantsLoadAtTheirOneValueAndNameThemselvesOtherwise) {
    // Records of earlier versions carry reference_step, re_relaxation, shifting_velocity and
    // higher_order_laplacian at one fixed value: the record reloads, and any other value is
    // refused naming the key and the value it must have.
    for (const char* scheme : {"swell", "textbook"}) {
        json j = minimal();
        j["solver"]["scheme"] = scheme;
        const Scene byDefault = parseScene(j);
        const json record = toJson(byDefault);
        EXPECT_EQ(record["solver"]["reference_step"], 0.0) << scheme;
        EXPECT_EQ(record["solver"]["re_relaxation"], byDefault.solver.model.reDensity) << scheme;
        EXPECT_EQ(record["solver"]["shifting_velocity"], false) << scheme;
        EXPECT_EQ(record["solver"]["higher_order_laplacian"], false) << scheme;
        EXPECT_EQ(toJson(parseScene(record)), record) << scheme;
    }
    const auto refused = [](const char* key, const json& value, const char* wants) {
        json j = minimal();
        j["solver"][key] = value;
        EXPECT_EQ(errorKey(j), std::string("solver.") + key) << value;
        const std::string msg = errorMessage(j);
        EXPECT_NE(msg.find(wants), std::string::npos) << msg;
    };
    refused("reference_step", 0.0005, "the only value is 0");
    refused("reference_step", "1 ms", "must be a number");
    refused("re_relaxation", 2.5, "the only value is 2.8");
    refused("shifting_velocity", true, "the only value is false");
    refused("higher_order_laplacian", true, "the only value is false");
    refused("higher_order_laplacian", "yes", "must be true or false");
    json t = minimal();
    t["solver"]["scheme"] = "textbook";
    t["solver"]["re_relaxation"] = 2.1; // the textbook scheme's re_density
    EXPECT_EQ(errorKey(t), "<accepted>");
    for (const char* gone : {"truncated_density", "shift_dead_band", "shift_close_pairs",
                             "shift_close_pairs_region", "shift_damping_wall_gain"}) {
        json j = minimal();
        j["solver"][gone] = 0.0;
        EXPECT_EQ(errorKey(j), std::string("solver.") + gone);
    }
}

TEST(Scene, SolverParamsDefaultIsTheSchemeAScenePicksWithoutOne) {
    // SolverParams{} and a scene without solver.scheme agree on every setting (the swell
    // scheme); schemeParams(Scheme::Textbook) is the reference scheme.
    const Scene parsed = parseScene(minimal());
    Scene plain = parsed;
    plain.solver = SolverParams{};
    plain.solver.time = parsed.solver.time; // minimal() sets dt and end_time
    EXPECT_EQ(toJson(plain), toJson(parsed));
    EXPECT_EQ(SolverParams{}.scheme, Scheme::Swell);
    json t = minimal();
    t["solver"]["scheme"] = "textbook";
    const Scene textbook = parseScene(t);
    plain.solver = schemeParams(Scheme::Textbook);
    plain.solver.time = textbook.solver.time;
    EXPECT_EQ(toJson(plain), toJson(textbook));
}

TEST(Scene, SchemeSetsTheModelAndKeysOverrideIt) {
    json j = minimal();
    const Scene byDefault = parseScene(j);
    EXPECT_EQ(byDefault.solver.scheme, Scheme::Swell);
    EXPECT_EQ(byDefault.solver.model.gradient, GradientModel::MinimumPressureCorrected);
    EXPECT_EQ(byDefault.solver.model.surfaceTest, SurfaceTest::Distribution);
    EXPECT_EQ(byDefault.solver.pressure.sourceTerm, SourceTerm::Mixed);
    EXPECT_DOUBLE_EQ(byDefault.solver.pressure.relaxation, 0.02);
    EXPECT_DOUBLE_EQ(byDefault.solver.model.shifting, 0.02);
    EXPECT_DOUBLE_EQ(byDefault.solver.model.collisionDistance, 0.8);
    EXPECT_DOUBLE_EQ(byDefault.solver.model.restitution, 0.0);
    EXPECT_DOUBLE_EQ(byDefault.solver.model.reDensity, 2.8);
    EXPECT_DOUBLE_EQ(toJson(byDefault)["solver"]["re_relaxation"].get<double>(), 2.8);
    EXPECT_DOUBLE_EQ(byDefault.solver.model.rePacking, 3.0);
    j["solver"]["scheme"] = "textbook";
    const Scene textbook = parseScene(j);
    EXPECT_EQ(textbook.solver.model.gradient, GradientModel::MinimumPressure);
    EXPECT_EQ(textbook.solver.model.surfaceTest, SurfaceTest::Density);
    EXPECT_EQ(textbook.solver.pressure.sourceTerm, SourceTerm::Relaxed);
    EXPECT_DOUBLE_EQ(textbook.solver.pressure.relaxation, 0.2);
    EXPECT_DOUBLE_EQ(textbook.solver.model.shifting, 0.0);
    EXPECT_DOUBLE_EQ(textbook.solver.model.collisionDistance, 0.5);
    EXPECT_DOUBLE_EQ(textbook.solver.model.restitution, 0.2);
    EXPECT_DOUBLE_EQ(textbook.solver.model.reDensity, 2.1);
    EXPECT_DOUBLE_EQ(toJson(textbook)["solver"]["re_relaxation"].get<double>(), 2.1);
    EXPECT_DOUBLE_EQ(textbook.solver.model.rePacking, 0.0);
    {
        json k = j;
        EXPECT_DOUBLE_EQ(toJson(parseScene(k))["solver"]["re_packing"].get<double>(), 0.0);
        k["solver"]["re_packing"] = 3.0;
        EXPECT_DOUBLE_EQ(parseScene(k).solver.model.rePacking, 3.0);
        EXPECT_DOUBLE_EQ(toJson(parseScene(k))["solver"]["re_packing"].get<double>(), 3.0);
        for (const double bad : {0.5, 1.0, -1.0, 11.0}) { // 0 (off) or above one spacing
            k["solver"]["re_packing"] = bad;
            const std::string msg = errorMessage(k);
            EXPECT_NE(msg.find("solver.re_packing"), std::string::npos) << bad << ": " << msg;
        }
    }
    j["solver"]["gradient_correction"] = true; // a key overrides its scheme's value
    EXPECT_EQ(parseScene(j).solver.model.gradient, GradientModel::MinimumPressureCorrected);
    EXPECT_EQ(toJson(parseScene(j))["solver"]["scheme"], "textbook");
}

TEST(Scene, UnknownSchemeAndUnsupportedCombinationsAreClearErrors) {
    json j = minimal();
    j["solver"]["scheme"] = "cmps";
    EXPECT_EQ(errorKey(j), "solver.scheme");
    const std::string unknown = errorMessage(j);
    EXPECT_NE(unknown.find("\"textbook\", \"swell\""), std::string::npos) << unknown;
    j = minimal();
    j["solver"]["scheme"] = "textbook";
    j["solver"]["shifting"] = 0.02; // shifting needs the distribution test's surface normals
    EXPECT_EQ(errorKey(j), "solver.shifting");
    j["solver"]["surface_test"] = "distribution";
    EXPECT_EQ(errorKey(j), "<accepted>");
    j["solver"]["surface_test"] = "neighbours";
    EXPECT_EQ(errorKey(j), "solver.surface_test");
    // The default scheme shifts: the density test alone is refused with a message that
    // names the shifting coefficient and how to turn it off.
    j = minimal();
    j["solver"]["surface_test"] = "density";
    EXPECT_EQ(errorKey(j), "solver.shifting");
    const std::string density = errorMessage(j);
    EXPECT_NE(density.find("C = 0.02"), std::string::npos) << density;
    EXPECT_NE(density.find("solver.shifting to 0"), std::string::npos) << density;
    j["solver"]["shifting"] = 0.0;
    EXPECT_EQ(errorKey(j), "<accepted>");
}

TEST(Scene, ShiftDampingIsTheDefaultSchemesAndNeedsShifting) {
    // The default scheme damps against the shift, the textbook scheme does not; without
    // shifting the default turns itself off, and asking for it by name is an error.
    json j = minimal();
    EXPECT_TRUE(parseScene(j).solver.model.shiftDamping);
    j["solver"]["shift_damping"] = false;
    EXPECT_FALSE(parseScene(j).solver.model.shiftDamping);
    j = minimal();
    j["solver"]["scheme"] = "textbook";
    EXPECT_FALSE(parseScene(j).solver.model.shiftDamping);
    j = minimal();
    j["solver"]["shifting"] = 0.0;
    const Scene unshifted = parseScene(j);
    EXPECT_FALSE(unshifted.solver.model.shiftDamping);
    EXPECT_EQ(toJson(parseScene(toJson(unshifted))), toJson(unshifted)); // the record reloads
    j["solver"]["shift_damping"] = true;
    EXPECT_EQ(errorKey(j), "solver.shift_damping");
    const std::string damping = errorMessage(j);
    EXPECT_NE(damping.find("solver.shifting is 0"), std::string::npos) << damping;
    j["solver"]["shifting"] = 0.02;
    EXPECT_EQ(errorKey(j), "<accepted>");
    j["solver"]["shift_damping"] = 1;
    EXPECT_EQ(errorKey(j), "solver.shift_damping");
}

TEST(Scene, ShiftDampingGainIsOptInAndRangeChecked) {
    // Neither scheme sets it (gain 1). It is range-checked, names itself in the error and
    // reloads from the scene record.
    for (const char* scheme : {"swell", "textbook"}) {
        json j = minimal();
        j["solver"]["scheme"] = scheme;
        EXPECT_EQ(parseScene(j).solver.model.shiftDampingGain, 1.0) << scheme;
    }
    json j = minimal();
    j["solver"]["shift_damping_gain"] = 2.0;
    const Scene calm = parseScene(j);
    EXPECT_EQ(calm.solver.model.shiftDampingGain, 2.0);
    EXPECT_EQ(toJson(calm)["solver"]["shift_damping_gain"], 2.0);
    EXPECT_EQ(toJson(parseScene(toJson(calm))), toJson(calm));
    // At its default it is left out of the record, so the record (and a checkpoint's
    // fingerprint) is what the builds before this key wrote.
    EXPECT_FALSE(toJson(parseScene(minimal()))["solver"].contains("shift_damping_gain"));
    expectSolverKeyRejects("shift_damping_gain", {0.0, -1.0, 10.5});
}

TEST(Scene, NumberBeyondADoubleIsASceneErrorNamingTheFile) {
    const swell::test::TempDir dir("swell_big_number_");
    const auto tmp = dir / "big.json";
    {
        std::FILE* f = std::fopen(tmp.c_str(), "w");
        std::fputs(R"({"geometry": {"particle_spacing": 1e400}})", f);
        std::fclose(f);
    }
    try {
        (void)loadScene(tmp);
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("big.json is not valid JSON"), std::string::npos);
    }
}

TEST(Scene, NestingAMillionLevelsDeepIsRefusedNamingTheFileOrTheKey) {
    // Printing such a value in a message would recurse once per level; it is refused before
    // it is parsed, in a scene file and in a --set value.
    const std::string deep = std::string(1000000, '[') + std::string(1000000, ']');
    const swell::test::TempDir dir("swell_deep_scene_");
    const auto tmp = dir / "deep.json";
    {
        std::ofstream f(tmp);
        f << R"({"name": )" << deep << "}";
    }
    try {
        (void)loadScene(tmp);
        FAIL() << "a scene nested 1,000,001 levels deep was accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("deep.json nests 1000001 levels deep"),
                  std::string::npos)
            << e.what();
    }
    json j = minimal();
    try {
        applyOverride(j, "name=" + deep);
        FAIL() << "a --set value nested 1,000,000 levels deep was accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.key(), "name");
        EXPECT_NE(std::string(e.what()).find("nests 1000000 levels deep"), std::string::npos)
            << e.what();
    }
}

TEST(Scene, ErrorsStayOnOneLine) {
    const auto message = [](const std::function<void()>& f) {
        try {
            f();
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("<no SceneError>");
    };
    json j = minimal();
    j["solver"]["a\nb"] = 1; // an unknown key holding a newline
    const std::string unknown = message([&] { (void)parseScene(j); });
    EXPECT_EQ(unknown, "scene key 'solver.a\\x0ab': unknown key");
    json k = minimal();
    const std::string utf8 =
        message([&] { applyOverride(k, std::string("name=\xff\xfe")); }); // not UTF-8
    EXPECT_NE(utf8.find("not valid UTF-8"), std::string::npos) << utf8;
    EXPECT_EQ(message([] { (void)loadScene("no\nsuch.json"); }),
              "cannot open scene file no\\x0asuch.json: No such file or directory");
    const swell::test::TempDir dir("swell_scene_dir_");
    EXPECT_EQ(message([&] { (void)loadScene(dir.path()); }),
              "scene file " + dir.path().string() + " is a directory, not a JSON file");
}

TEST(Scene, BedProfileIsReadRoundTripsAndNamesItsPoints) {
    json j = minimal();
    j["geometry"]["bed"] = json::array({{0.2, 0.0}, {0.5, 0.06}});
    const Scene a = parseScene(j);
    ASSERT_EQ(a.geometry.bed.size(), 2u);
    EXPECT_EQ(a.geometry.bed[1].x, 0.5);
    EXPECT_EQ(a.geometry.bed[1].y, 0.06);
    EXPECT_EQ(toJson(parseScene(toJson(a))), toJson(a));
    // No profile writes no bed: scenes without one keep their recorded form.
    EXPECT_FALSE(toJson(parseScene(minimal()))["geometry"].contains("bed"));

    j["geometry"]["bed"] = json::array({{0.2, 0.0}, {0.5}});
    EXPECT_EQ(errorKey(j), "geometry.bed[1]");
    j["geometry"]["bed"] = json::array({{0.2, 0.0}, {0.5, "high"}});
    EXPECT_EQ(errorKey(j), "geometry.bed[1]");
    j["geometry"]["bed"] = {{"x", 0.2}};
    EXPECT_EQ(errorKey(j), "geometry.bed");
    // A piston is the back wall above the bed: the profile must start at the tank's y0 there.
    j = minimal();
    j["piston"] = {{"kind", "sinusoidal"}, {"period", 1.0}, {"stroke", 0.02}};
    j["geometry"]["bed"] = json::array({{0.0, 0.02}, {0.5, 0.02}});
    EXPECT_EQ(errorKey(j), "geometry.bed");
    j["geometry"]["bed"] = json::array({{0.2, 0.0}, {0.5, 0.02}});
    EXPECT_EQ(errorKey(j), "<accepted>");
}
