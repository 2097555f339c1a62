#include "swell/bake/scene.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "swell/bake/error.h"
#include "swell/cache/json_depth.h"

namespace swell::bake {
namespace {

using nlohmann::json;

/// A value as an error message shows it: JSON on one line, invalid UTF-8 replaced, cut at 60
/// characters.
std::string shown(const json& v) {
    std::string t = v.dump(-1, ' ', false, json::error_handler_t::replace);
    if (t.size() > 60)
        t = t.substr(0, 57) + "...";
    return t;
}

/// A key as an error message shows it: control characters escaped, so the message is one line.
std::string printable(const std::string& k) {
    std::string out;
    for (const char c : k) {
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
        else
            out += c;
    }
    return out;
}

/// Reads the keys of one JSON object, remembering which were used so that
/// finish() can reject the unknown ones.
class Section {
public:
    Section(const json& j, std::string path) : m_json(j), m_path(std::move(path)) {
        if (!m_json.is_object())
            throw SceneError(m_path, "must be a JSON object");
    }

    std::string key(const std::string& k) const {
        return m_path.empty() ? printable(k) : m_path + "." + printable(k);
    }
    bool has(const std::string& k) const { return m_json.contains(k); }

    const json* get(const std::string& k) {
        m_used.insert(k);
        const auto it = m_json.find(k);
        return it == m_json.end() ? nullptr : &*it;
    }

    /// A finite number within [lo, hi] (bounds exclusive where asked).
    double number(const std::string& k, double def, double lo, double hi, bool loOpen = false,
                  const char* unit = "") {
        const json* v = get(k);
        if (!v)
            return def;
        if (!v->is_number())
            throw SceneError(key(k), fmt::format("must be a number{}, got {}", unit, shown(*v)));
        const double x = v->get<double>();
        if (!std::isfinite(x) || x < lo || x > hi || (loOpen && x == lo)) {
            throw SceneError(key(k), fmt::format("{} is out of range: must be {} {}{}", x,
                                                 loOpen ? ">" : ">=", lo,
                                                 hi < std::numeric_limits<double>::max()
                                                     ? fmt::format(" and <= {}", hi)
                                                     : std::string()));
        }
        return x;
    }

    int integer(const std::string& k, int def, int lo, int hi) {
        const json* v = get(k);
        if (!v)
            return def;
        if (!v->is_number_integer())
            throw SceneError(key(k), fmt::format("must be an integer, got {}", shown(*v)));
        const auto x = v->get<long long>();
        if (x < lo || x > hi) {
            throw SceneError(key(k),
                             fmt::format("{} is out of range: must be in [{}, {}]", x, lo, hi));
        }
        return static_cast<int>(x);
    }

    bool boolean(const std::string& k, bool def) {
        const json* v = get(k);
        if (!v)
            return def;
        if (!v->is_boolean())
            throw SceneError(key(k), fmt::format("must be true or false, got {}", shown(*v)));
        return v->get<bool>();
    }

    std::string string(const std::string& k, const std::string& def) {
        const json* v = get(k);
        if (!v)
            return def;
        if (!v->is_string())
            throw SceneError(key(k), fmt::format("must be a string, got {}", shown(*v)));
        return v->get<std::string>();
    }

    template <typename E>
    E enumeration(const std::string& k, E def, std::initializer_list<E> values) {
        const json* v = get(k);
        if (!v)
            return def;
        std::string names;
        for (E e : values)
            names += (names.empty() ? "\"" : ", \"") + std::string(toString(e)) + "\"";
        if (!v->is_string())
            throw SceneError(key(k), fmt::format("must be one of {}, got {}", names, shown(*v)));
        const auto s = v->get<std::string>();
        for (E e : values) {
            if (toString(e) == s)
                return e;
        }
        throw SceneError(key(k), fmt::format("unknown value \"{}\": must be one of {}", s, names));
    }

    void finish() const {
        for (const auto& [k, v] : m_json.items()) {
            if (!m_used.count(k))
                throw SceneError(key(k), "unknown key");
        }
    }

private:
    const json& m_json;
    std::string m_path;
    std::set<std::string> m_used;
};

constexpr double kInf = std::numeric_limits<double>::max();

/// A rectangle {x0, y0, x1, y1} (m); with `top`, a water rectangle, which may also give its
/// cosine top as "surface": {"amplitude", "wavelength"} (m).
Box readBox(const json& j, const std::string& path, CosineTop* top = nullptr) {
    Section s(j, path);
    Box b;
    if (top) {
        if (const json* v = s.get("surface")) {
            if (!v->is_object())
                throw SceneError(s.key("surface"),
                                 "must be an object {\"amplitude\", \"wavelength\"} (m)");
            Section t(*v, s.key("surface"));
            top->amplitude = t.number("amplitude", 0.0, -kInf, kInf, false, " (m)");
            top->wavelength = t.number("wavelength", 0.0, 0.0, kInf, true, " (m)");
            t.finish();
        }
    }
    for (const char* k : {"x0", "y0", "x1", "y1"}) {
        if (!s.has(k))
            throw SceneError(s.key(k), "missing (a rectangle needs x0, y0, x1, y1 in m)");
    }
    b.x0 = s.number("x0", 0.0, -kInf, kInf, false, " (m)");
    b.y0 = s.number("y0", 0.0, -kInf, kInf, false, " (m)");
    b.x1 = s.number("x1", 0.0, -kInf, kInf, false, " (m)");
    b.y1 = s.number("y1", 0.0, -kInf, kInf, false, " (m)");
    s.finish();
    if (!(b.x1 > b.x0))
        throw SceneError(path,
                         fmt::format("empty rectangle: x1 = {} must exceed x0 = {}", b.x1, b.x0));
    if (!(b.y1 > b.y0))
        throw SceneError(path,
                         fmt::format("empty rectangle: y1 = {} must exceed y0 = {}", b.y1, b.y0));
    return b;
}

std::vector<Box> readBoxes(Section& parent, const std::string& k) {
    std::vector<Box> out;
    const json* v = parent.get(k);
    if (!v)
        return out;
    if (!v->is_array())
        throw SceneError(parent.key(k), "must be an array of rectangles {x0, y0, x1, y1}");
    for (std::size_t i = 0; i < v->size(); ++i) {
        out.push_back(readBox((*v)[i], fmt::format("{}[{}]", parent.key(k), i)));
    }
    return out;
}

/// geometry.bed: an array of points [x, y] (m); the order and ranges are the geometry's to
/// check (generateGeometry), which names the point.
std::vector<BedPoint> readBed(Section& parent) {
    std::vector<BedPoint> out;
    const json* v = parent.get("bed");
    if (!v)
        return out;
    if (!v->is_array())
        throw SceneError("geometry.bed", "must be an array of points [x, y] (m)");
    for (std::size_t i = 0; i < v->size(); ++i) {
        const json& p = (*v)[i];
        const std::string key = fmt::format("geometry.bed[{}]", i);
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
            throw SceneError(key, fmt::format("must be a point [x, y] (m), got {}", shown(p)));
        out.push_back(BedPoint{p[0].get<double>(), p[1].get<double>()});
    }
    return out;
}

json boxJson(const Box& b) {
    return json{{"x0", b.x0}, {"y0", b.y0}, {"x1", b.x1}, {"y1", b.y1}};
}

/// geometry.water: its rectangles and their tops (GeometryParams::waterTops).
void readWater(Section& parent, GeometryParams& g) {
    const json* v = parent.get("water");
    if (!v->is_array())
        throw SceneError("geometry.water", "must be an array of rectangles {x0, y0, x1, y1}");
    g.water.clear();
    g.waterTops.clear();
    for (std::size_t i = 0; i < v->size(); ++i) {
        CosineTop top;
        g.water.push_back(readBox((*v)[i], fmt::format("geometry.water[{}]", i), &top));
        g.waterTops.push_back(top);
    }
}

/// Keys that scene records written by earlier versions carry at one fixed value. They are
/// accepted at that value, so those records and their checkpoints still load; any other value
/// names a scheme this solver no longer has.
void readRecordedConstants(Section& s, const ModelParams& m) {
    const auto fixed = [&](const char* k, double value, const char* why) {
        const double x = s.number(k, value, -kInf, kInf);
        if (x != value) {
            throw SceneError(s.key(k), fmt::format("{:g} is not supported: the only value is "
                                                   "{:g} ({}); leave the key out",
                                                   x, value, why));
        }
    };
    fixed("reference_step", 0.0, "gamma and C act per step");
    fixed("re_relaxation", m.reDensity,
          "the density relaxation uses the density radius, solver.re_density");
    const auto off = [&](const char* k, const char* why) {
        if (s.boolean(k, false)) {
            throw SceneError(s.key(k),
                             fmt::format("true is not supported: the only value is false ({}); "
                                         "leave the key out",
                                         why));
        }
    };
    off("shifting_velocity", "the shifting moves positions only");
    off("higher_order_laplacian", "the Laplacian is eq. (4)'s");
}

/// The scene's top-level keys name, description and seed.
void readHeader(Section& top, Scene& scene) {
    scene.name = top.string("name", "");
    scene.description = top.string("description", "");
    if (const json* sd = top.get("seed")) {
        if (!sd->is_number_unsigned() && !(sd->is_number_integer() && sd->get<long long>() >= 0)) {
            throw SceneError("seed",
                             fmt::format("must be a non-negative integer, got {}", shown(*sd)));
        }
        scene.seed = sd->get<std::uint64_t>();
    }
}

/// An optional section's JSON: the object given, or an empty one (every key at its default).
const json& orEmpty(const json* v) {
    static const json kEmpty = json::object();
    return v ? *v : kEmpty;
}

/// physics: density, kinematic viscosity, gravity.
void readPhysics(const json* phys, PhysicsParams& p) {
    Section s(orEmpty(phys), "physics");
    p.density = s.number("density", p.density, 0.0, kInf, true, " (kg/m^3)");
    p.kinematicViscosity =
        s.number("kinematic_viscosity", p.kinematicViscosity, 0.0, kInf, false, " (m^2/s)");
    p.gravity = s.number("gravity", p.gravity, 0.0, kInf, false, " (m/s^2)");
    s.finish();
}

/// geometry: the spacing, tank, water, solids, bed, wall layers, jitter and domain.
void readGeometry(const json* geo, GeometryParams& g) {
    if (!geo)
        throw SceneError("geometry", "missing: a scene needs at least one water rectangle");
    Section s(*geo, "geometry");
    g.particleSpacing = s.number("particle_spacing", g.particleSpacing, 0.0, kInf, true, " (m)");
    if (const json* t = s.get("tank"))
        g.tank = readBox(*t, "geometry.tank");
    if (!s.has("water"))
        throw SceneError("geometry.water", "missing: a scene needs at least one water rectangle");
    readWater(s, g);
    if (g.water.empty())
        throw SceneError("geometry.water", "is empty: a scene needs at least one water rectangle");
    g.solids = readBoxes(s, "solids");
    g.bed = readBed(s);
    g.wallLayers = s.integer("wall_layers", g.wallLayers, 1, 10);
    g.dummyLayers = s.integer("dummy_layers", g.dummyLayers, 0, 10);
    g.jitter = s.number("jitter", g.jitter, 0.0, 0.1, false, " (l0)");
    if (const json* d = s.get("domain"))
        g.domain = readBox(*d, "geometry.domain");
    s.finish();
}

/// solver's time-step keys, and the run's end time and expected speed listed among them.
void readTimeStep(Section& s, TimeStepParams& t, RunParams& run) {
    t.dt = s.number("dt", t.dt, 0.0, kInf, true, " (s)");
    run.endTime = s.number("end_time", run.endTime, 0.0, kInf, true, " (s)");
    t.adaptive = s.boolean("adaptive_dt", t.adaptive);
    t.courantTarget = s.number("courant_target", t.courantTarget, 0.0, 1.0, true);
    t.courantLimit = s.number("courant_limit", t.courantLimit, 0.0, 2.0, true);
    t.substepCourant = s.number("substep_courant", t.substepCourant, 0.0, 1.0);
    run.expectedSpeed = s.number("expected_speed", run.expectedSpeed, 0.0, kInf, false, " (m/s)");
}

/// Refuses particle shifting without the distribution surface test, and shift damping without
/// shifting where the scene asks for it (the scheme's default turns itself off).
void checkShifting(const Section& s, ModelParams& m) {
    if (m.shifting > 0.0 && m.surfaceTest != SurfaceTest::Distribution) {
        throw SceneError("solver.shifting",
                         fmt::format("particle shifting (C = {:g}) needs solver.surface_test "
                                     "\"distribution\" (it moves free-surface particles "
                                     "along the surface normal that test finds); set "
                                     "solver.shifting to 0 to use another surface test",
                                     m.shifting));
    }
    // Without shifting there is nothing to damp: the scheme's default turns itself off,
    // and asking for it by name is an error.
    if (m.shiftDamping && !(m.shifting > 0.0)) {
        if (s.has("shift_damping")) {
            throw SceneError("solver.shift_damping",
                             "takes from a free-surface particle the velocity its shift "
                             "undoes, and solver.shifting is 0: set a shifting coefficient "
                             "or set this to false");
        }
        m.shiftDamping = false;
    }
}

/// solver's particle-model keys (radii, surface test, collisions, shifting, gradient), with the
/// pressure keys relaxation, compressibility and source_term read in the order listed among them.
void readModel(Section& s, ModelParams& m, PressureParams& e) {
    m.reDensity = s.number("re_density", m.reDensity, 1.0, 10.0, true, " (l0)");
    m.reLaplacian = s.number("re_laplacian", m.reLaplacian, 1.0, 10.0, true, " (l0)");
    m.rePacking = s.number("re_packing", m.rePacking, 0.0, 10.0, false, " (l0)");
    if (m.rePacking > 0.0 && m.rePacking <= 1.0) {
        throw SceneError(
            "solver.re_packing",
            fmt::format("{:g} is out of range: must be 0 (off) or > 1 (l0)", m.rePacking));
    }
    m.surfaceThreshold = s.number("surface_threshold", m.surfaceThreshold, 0.0, 1.0, true);
    e.relaxation = s.number("relaxation", e.relaxation, 0.0, 1.0, true);
    e.compressibility = s.number("compressibility", e.compressibility, 0.0, kInf, false, " (1/Pa)");
    m.collisionDistance =
        s.number("collision_distance", m.collisionDistance, 0.0, 1.0, false, " (l0)");
    m.restitution = s.number("restitution", m.restitution, 0.0, 1.0);
    e.sourceTerm =
        s.enumeration("source_term", e.sourceTerm, {SourceTerm::Relaxed, SourceTerm::Mixed});
    m.surfaceTest = s.enumeration("surface_test", m.surfaceTest,
                                  {SurfaceTest::Density, SurfaceTest::Distribution});
    m.sparseThreshold = s.number("sparse_threshold", m.sparseThreshold, 0.0, 1.0, true);
    m.distributionThreshold =
        s.number("distribution_threshold", m.distributionThreshold, 0.0, 10.0, false);
    m.shifting = s.number("shifting", m.shifting, 0.0, 1.0, false);
    m.shiftDamping = s.boolean("shift_damping", m.shiftDamping);
    m.shiftDampingGain = s.number("shift_damping_gain", m.shiftDampingGain, 0.0, 10.0, true);
    readRecordedConstants(s, m);
    checkShifting(s, m);
    const bool corrected = s.boolean("gradient_correction", usesCorrectiveMatrix(m.gradient));
    const bool symmetric = s.boolean("symmetric_gradient", usesSymmetricPairs(m.gradient));
    m.gradient = gradientModel(symmetric, corrected);
}

/// solver's pressure-solve keys (preconditioner, tolerance, iterations) and neighbour keys.
void readPressureSolve(Section& s, PressureParams& e, NeighborParams& nb) {
    e.preconditioner =
        s.enumeration("preconditioner", e.preconditioner,
                      {Preconditioner::Jacobi, Preconditioner::SymmetricGaussSeidel,
                       Preconditioner::IncompleteCholesky, Preconditioner::TwoLevel});
    e.tolerance = s.number("ppe_tolerance", e.tolerance, 0.0, 0.5, true);
    e.maxIterations = s.integer("ppe_max_iterations", e.maxIterations, 1, 1000000);
    nb.skin = s.number("neighbor_skin", nb.skin, 0.0, 2.0, false, " (l0)");
    nb.maxNeighbors = s.integer("max_neighbors", nb.maxNeighbors, 8, 1024);
}

/// solver: the scheme, then the time-step, model, pressure-solve and neighbour keys.
void readSolver(const json* sol, Scene& scene) {
    Section s(orEmpty(sol), "solver");
    SolverParams& p = scene.solver;
    // The scheme sets the model and pressure defaults; the keys below override them.
    p = schemeParams(s.enumeration("scheme", Scheme::Swell, {Scheme::Textbook, Scheme::Swell}));
    readTimeStep(s, p.time, scene.run);
    readModel(s, p.model, p.pressure);
    readPressureSolve(s, p.pressure, p.neighbors);
    s.finish();
}

/// output: the frame interval, the classification ratios, the gauges and the still level.
void readOutput(const json* outp, OutputParams& o) {
    Section s(orEmpty(outp), "output");
    o.frameInterval = s.number("frame_interval", o.frameInterval, 0.0, kInf, true, " (s)");
    o.splashRatio = s.number("splash_ratio", o.splashRatio, 0.0, 1.0, true);
    o.surfaceRatio = s.number("surface_ratio", o.surfaceRatio, 0.0, 1.0, true);
    if (const json* g = s.get("gauges")) {
        if (!g->is_array())
            throw SceneError("output.gauges", "must be an array of x positions (m)");
        for (std::size_t i = 0; i < g->size(); ++i) {
            const json& v = (*g)[i];
            if (!v.is_number() || !std::isfinite(v.get<double>())) {
                throw SceneError(fmt::format("output.gauges[{}]", i),
                                 fmt::format("must be a number (m), got {}", shown(v)));
            }
            o.gauges.push_back(v.get<double>());
        }
    }
    if (s.has("still_water_level")) {
        o.stillWaterLevel = s.number("still_water_level", 0.0, -kInf, kInf, false, " (m)");
    }
    s.finish();
    if (!(o.splashRatio < o.surfaceRatio)) {
        throw SceneError("output.splash_ratio",
                         fmt::format("d1 = {} must be below output.surface_ratio d2 = {}",
                                     o.splashRatio, o.surfaceRatio));
    }
}

/// The piston's forward travel (m) against half the tank width; a solitary piston's depth is
/// the still water over the tank's bed, and its stroke what its motion reaches in the end.
void checkPistonTravel(PistonParams& p, const Scene& scene) {
    const bool solitary = p.kind == PistonKind::Solitary;
    if (solitary) {
        // Goring's stroke is made for the water it pushes: the still water over the bed.
        p.depth = stillWaterLevel(scene) - scene.geometry.tank->y0;
        p.gravity = scene.physics.gravity;
        if (!(p.depth > 0.0))
            throw SceneError("piston.kind",
                             "solitary needs still water above the tank's bed: its depth");
    }
    double solitaryStroke = 0.0;
    try {
        const PistonMotion motion(p, scene.run.endTime);
        if (solitary)
            solitaryStroke = motion.at(kInf).displacement;
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what(); // "piston.<field>: problem"
        const auto colon = what.find(':');
        throw SceneError(what.substr(0, colon),
                         colon == std::string::npos ? what : what.substr(colon + 2));
    }
    const bool sinus = p.kind == PistonKind::Sinusoidal;
    const double forward = sinus ? 0.5 * p.stroke : solitary ? solitaryStroke : p.strokeMax;
    if (forward >= 0.5 * scene.geometry.tank->width()) {
        throw SceneError(
            sinus ? "piston.stroke" : (solitary ? "piston.height" : "piston.stroke_max"),
            fmt::format("the piston would travel {} m, at least half the tank width {} m", forward,
                        scene.geometry.tank->width()));
    }
}

/// piston: the wave maker, the tank's back wall above the bed.
void readPiston(const json& pj, Scene& scene) {
    Section s(pj, "piston");
    PistonParams p;
    p.kind = s.enumeration("kind", p.kind,
                           {PistonKind::Sinusoidal, PistonKind::Random, PistonKind::Solitary});
    p.period = s.number("period", p.period, 0.0, kInf, true, " (s)");
    p.stroke = s.number("stroke", p.stroke, 0.0, kInf, false, " (m)");
    p.periodMin = s.number("period_min", p.periodMin, 0.0, kInf, true, " (s)");
    p.periodMax = s.number("period_max", p.periodMax, 0.0, kInf, true, " (s)");
    p.strokeMin = s.number("stroke_min", p.strokeMin, 0.0, kInf, false, " (m)");
    p.strokeMax = s.number("stroke_max", p.strokeMax, 0.0, kInf, false, " (m)");
    p.rampTime = s.number("ramp_time", p.rampTime, 0.0, kInf, false, " (s)");
    p.height = s.number("height", p.height, 0.0, kInf, true, " (m)");
    s.finish();
    p.seed = scene.seed;
    if (!scene.geometry.tank)
        throw SceneError("piston", "needs geometry.tank: the piston is the tank's back wall");
    if (bedHeight(scene.geometry, scene.geometry.tank->x0) != scene.geometry.tank->y0)
        throw SceneError("geometry.bed",
                         "must start at the tank's y0 at its back wall when the scene has a "
                         "piston (the piston is the back wall above the bed)");
    checkPistonTravel(p, scene);
    // Room behind the back wall for a piston that moves back (sinusoidal: S/2).
    scene.geometry.bedExtensionBack = p.kind == PistonKind::Sinusoidal ? 0.5 * p.stroke : 0.0;
    scene.piston = p;
}

/// recycling: the inflow and outflow of a channel, in place of a piston.
void readRecycling(const json& rj, Scene& scene) {
    Section s(rj, "recycling");
    RecyclingParams r;
    r.inflowX1 = s.number("inflow_x1", r.inflowX1, -kInf, kInf, false, " (m)");
    r.velocity = s.number("velocity", r.velocity, -kInf, kInf, false, " (m/s)");
    r.outflowX = s.number("outflow_x", r.outflowX, -kInf, kInf, false, " (m)");
    s.finish();
    if (!scene.geometry.tank)
        throw SceneError("recycling", "needs geometry.tank (the channel)");
    const Box& t = *scene.geometry.tank;
    const double l0 = scene.geometry.particleSpacing;
    if (!(r.inflowX1 >= t.x0 + 2.0 * l0)) {
        throw SceneError("recycling.inflow_x1",
                         fmt::format("{} m must be at least two spacings past the tank's "
                                     "back wall x0 = {} m",
                                     r.inflowX1, t.x0));
    }
    if (!(r.outflowX > r.inflowX1 && r.outflowX <= t.x1 - l0)) {
        throw SceneError("recycling.outflow_x",
                         fmt::format("{} m must lie between inflow_x1 = {} m and the "
                                     "front wall x1 - l0 = {} m",
                                     r.outflowX, r.inflowX1, t.x1 - l0));
    }
    if (scene.piston)
        throw SceneError("recycling", "a scene has either a piston or recycling, not both");
    scene.recycling = r;
}

/// Refuses a gauge outside the tank.
void checkGauges(const Scene& scene) {
    for (std::size_t i = 0; i < scene.output.gauges.size(); ++i) {
        const double x = scene.output.gauges[i];
        if (scene.geometry.tank && (x < scene.geometry.tank->x0 || x > scene.geometry.tank->x1)) {
            throw SceneError(fmt::format("output.gauges[{}]", i),
                             fmt::format("x = {} m lies outside the tank [{}, {}] m", x,
                                         scene.geometry.tank->x0, scene.geometry.tank->x1));
        }
    }
}

/// Time step against the Courant limit for the expected speed.
void checkCourant(const Scene& scene) {
    const double speed = expectedSpeed(scene);
    const TimeStepParams& time = scene.solver.time;
    const double courant = speed * time.dt / scene.geometry.particleSpacing;
    if (!time.adaptive && courant > time.courantLimit) {
        throw SceneError(
            "solver.dt",
            fmt::format("dt = {} s gives Courant number {:.3g} = {:.3g} m/s x dt / {} m at "
                        "the expected speed, above solver.courant_limit {}; use dt <= {:.3g} s "
                        "or solver.adaptive_dt",
                        time.dt, courant, speed, scene.geometry.particleSpacing, time.courantLimit,
                        time.courantLimit * scene.geometry.particleSpacing / speed));
    }
}

} // namespace

double expectedSpeed(const Scene& scene) {
    if (scene.run.expectedSpeed > 0.0)
        return scene.run.expectedSpeed;
    double lo = kInf, hi = -kInf;
    for (const Box& b : scene.geometry.water) {
        lo = std::min(lo, b.y0);
        hi = std::max(hi, b.y1);
    }
    const double h = hi > lo ? hi - lo : 0.0;
    return 2.0 * std::sqrt(scene.physics.gravity * h); // Ritter: dry-bed dam-break front speed
}

Scene parseScene(const json& j) {
    Scene scene;
    Section top(j, "");
    readHeader(top, scene);
    readPhysics(top.get("physics"), scene.physics);
    readGeometry(top.get("geometry"), scene.geometry);
    readSolver(top.get("solver"), scene);
    readOutput(top.get("output"), scene.output);
    if (const json* pj = top.get("piston"))
        readPiston(*pj, scene);
    if (const json* rj = top.get("recycling"))
        readRecycling(*rj, scene);
    checkGauges(scene);
    top.finish();

    // Geometry: generate once so bad rectangles are reported now, naming their key.
    (void)generateGeometry(scene.geometry);

    checkCourant(scene);
    return scene;
}

json parseSceneJson(std::string_view text, const std::string& source) {
    if (const std::string deep = cache::jsonDepthProblem(text); !deep.empty())
        throw SceneError("", fmt::format("{} {}", printable(source), deep));
    try {
        return json::parse(text);
    } catch (const json::exception& e) { // syntax, and numbers beyond a double (out_of_range)
        throw SceneError(
            "", fmt::format("{} is not valid JSON: {}", printable(source), printable(e.what())));
    }
}

Scene loadScene(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        throw SceneError("", fmt::format("scene file {} is a directory, not a JSON file",
                                         printable(path.string())));
    }
    std::ifstream in(path);
    if (!in) {
        throw SceneError("", fmt::format("cannot open scene file {}: {}", printable(path.string()),
                                         std::strerror(errno)));
    }
    std::stringstream buffer;
    buffer << in.rdbuf();
    json j = parseSceneJson(buffer.str(), path.string());
    for (const std::string& o : overrides)
        applyOverride(j, o);
    return parseScene(j);
}

json toJson(const Scene& sc) {
    const GeometryParams& g = sc.geometry;
    json water = json::array();
    for (std::size_t w = 0; w < g.water.size(); ++w) {
        json b = boxJson(g.water[w]);
        if (const CosineTop top = waterTop(g, w); top.amplitude != 0.0)
            b["surface"] = {{"amplitude", top.amplitude}, {"wavelength", top.wavelength}};
        water.push_back(std::move(b));
    }
    json solids = json::array();
    for (const Box& b : g.solids)
        solids.push_back(boxJson(b));
    json geo{{"particle_spacing", g.particleSpacing},
             {"water", water},
             {"solids", solids},
             {"wall_layers", g.wallLayers},
             {"dummy_layers", g.dummyLayers},
             {"jitter", g.jitter}};
    if (g.tank)
        geo["tank"] = boxJson(*g.tank);
    if (!g.bed.empty()) {
        json bed = json::array();
        for (const BedPoint& p : g.bed)
            bed.push_back(json::array({p.x, p.y}));
        geo["bed"] = std::move(bed);
    }
    if (g.domain)
        geo["domain"] = boxJson(*g.domain);
    const SolverParams& s = sc.solver;
    json output{{"frame_interval", sc.output.frameInterval},
                {"splash_ratio", sc.output.splashRatio},
                {"surface_ratio", sc.output.surfaceRatio},
                {"gauges", sc.output.gauges}};
    if (sc.output.stillWaterLevel)
        output["still_water_level"] = *sc.output.stillWaterLevel;
    json out{
        {"name", sc.name},
        {"description", sc.description},
        {"physics",
         {{"density", sc.physics.density},
          {"kinematic_viscosity", sc.physics.kinematicViscosity},
          {"gravity", sc.physics.gravity}}},
        {"geometry", geo},
        {"solver",
         {{"scheme", std::string(toString(s.scheme))},
          {"dt", s.time.dt},
          {"end_time", sc.run.endTime},
          {"adaptive_dt", s.time.adaptive},
          {"courant_target", s.time.courantTarget},
          {"courant_limit", s.time.courantLimit},
          {"substep_courant", s.time.substepCourant},
          {"reference_step", 0.0}, // recorded constants: readRecordedConstants
          {"expected_speed", sc.run.expectedSpeed},
          {"re_density", s.model.reDensity},
          {"re_laplacian", s.model.reLaplacian},
          {"re_relaxation", s.model.reDensity},
          {"re_packing", s.model.rePacking},
          {"surface_threshold", s.model.surfaceThreshold},
          {"relaxation", s.pressure.relaxation},
          {"compressibility", s.pressure.compressibility},
          {"collision_distance", s.model.collisionDistance},
          {"restitution", s.model.restitution},
          {"source_term", std::string(toString(s.pressure.sourceTerm))},
          {"gradient_correction", usesCorrectiveMatrix(s.model.gradient)},
          {"symmetric_gradient", usesSymmetricPairs(s.model.gradient)},
          {"surface_test", std::string(toString(s.model.surfaceTest))},
          {"sparse_threshold", s.model.sparseThreshold},
          {"distribution_threshold", s.model.distributionThreshold},
          {"shifting", s.model.shifting},
          {"shifting_velocity", false},
          {"shift_damping", s.model.shiftDamping},
          {"higher_order_laplacian", false},
          {"preconditioner", std::string(toString(s.pressure.preconditioner))},
          {"ppe_tolerance", s.pressure.tolerance},
          {"ppe_max_iterations", s.pressure.maxIterations},
          {"neighbor_skin", s.neighbors.skin},
          {"max_neighbors", s.neighbors.maxNeighbors}}},
        {"output", output},
        {"seed", sc.seed},
    };
    // Keys added without a change of the numerics are recorded only when set off their
    // default, so the record (and the checkpoint fingerprint made from it) of a scene that
    // leaves them alone is what the builds before them wrote, and such a bake resumes across
    // the upgrade (docs/scenes.md "Checkpoints"). Absent, they reload as their default.
    const ModelParams plain;
    if (s.model.shiftDampingGain != plain.shiftDampingGain)
        out["solver"]["shift_damping_gain"] = s.model.shiftDampingGain;
    if (sc.piston) {
        const PistonParams& p = *sc.piston;
        out["piston"] = json{{"kind", std::string(toString(p.kind))},
                             {"period", p.period},
                             {"stroke", p.stroke},
                             {"period_min", p.periodMin},
                             {"period_max", p.periodMax},
                             {"stroke_min", p.strokeMin},
                             {"stroke_max", p.strokeMax},
                             {"ramp_time", p.rampTime}};
        if (p.kind == PistonKind::Solitary) // only there, so other scenes serialize as before
            out["piston"]["height"] = p.height;
    }
    if (sc.recycling) {
        const RecyclingParams& r = *sc.recycling;
        out["recycling"] =
            json{{"inflow_x1", r.inflowX1}, {"velocity", r.velocity}, {"outflow_x", r.outflowX}};
    }
    return out;
}

double stillWaterLevel(const Scene& scene) {
    if (scene.output.stillWaterLevel)
        return *scene.output.stillWaterLevel;
    double top = -kInf;
    for (const Box& b : scene.geometry.water)
        top = std::max(top, b.y1);
    return top;
}

void applyOverride(json& j, const std::string& assignment) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
        throw SceneError("", fmt::format("override {} must look like section.key=value",
                                         shown(json(printable(assignment)))));
    }
    const std::string path = assignment.substr(0, eq);
    const std::string text = assignment.substr(eq + 1);
    if (const std::string deep = cache::jsonDepthProblem(text); !deep.empty())
        throw SceneError(printable(path), "override value " + deep);
    json value;
    try {
        value = json::parse(text);
    } catch (const json::exception&) {
        value = text;
        try {
            (void)value.dump(); // throws on invalid UTF-8, which no scene file can hold either
        } catch (const json::exception&) {
            throw SceneError(printable(path),
                             fmt::format("override value {} is not valid UTF-8", shown(value)));
        }
    }
    json* node = &j;
    std::size_t start = 0;
    while (true) {
        const auto dot = path.find('.', start);
        const std::string part =
            path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
        if (part.empty())
            throw SceneError(printable(path), "empty key in override");
        if (!node->is_object())
            throw SceneError(printable(path),
                             "override goes through a value that is not an object");
        if (dot == std::string::npos) {
            (*node)[part] = value;
            return;
        }
        node = &(*node)[part];
        if (node->is_null())
            *node = json::object();
        start = dot + 1;
    }
}

MpsSolver makeSolver(const Scene& scene) {
    GeneratedGeometry geo = generateGeometry(scene.geometry);
    if (scene.geometry.jitter > 0.0) {
        jitterWater(geo.particles, scene.geometry.jitter * scene.geometry.particleSpacing,
                    scene.seed);
    }
    MpsSolver solver(scene.physics, scene.solver, std::move(geo.particles),
                     scene.geometry.particleSpacing, geo.domain);
    if (scene.piston) {
        // Paper Sec. 3.3.1: the pushing wall (the tank's back wall) moves back and forth.
        PistonMotion motion(*scene.piston, scene.run.endTime);
        solver.setMovingWall(
            MovingWall{std::move(geo.backWall), [motion](double t) { return motion.at(t); }});
    }
    if (scene.recycling) {
        // Paper Sec. 3.3.2: inflow zone at the channel's upstream end (the driver recycles).
        const Box& t = *scene.geometry.tank;
        const Box& d = solver.domain();
        solver.setInflow(Box{t.x0, d.y0, scene.recycling->inflowX1, d.y1},
                         scene.recycling->velocity);
    }
    return solver;
}

} // namespace swell::bake
