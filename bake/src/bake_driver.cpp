#include "swell/bake/bake_driver.h"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>

#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "swell/bake/checkpoint.h"
#include "swell/bake/classification.h"
#include "swell/bake/error.h"
#include "swell/bake/numerics_version.h"
#include "swell/bake/probes.h"
#include "swell/bake/replay_window.h"
#include "swell/bake/solver_run.h"
#include "swell/bake/spill.h"
#include "swell/bake/wave_theory.h"
#include "swell/cache/checked_write.h"
#include "swell/cache/output_lock.h"
#include "swell/cache/writer.h"

namespace swell::bake {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Probes CSV, kept in memory and written (to a temporary name, renamed) when the bake
/// completes: a probes file is there only whole.
class ProbeFile {
public:
    ProbeFile(const std::filesystem::path& path, std::span<const double> gauges) : m_path(path) {
        if (!path.empty())
            m_text = probeCsvHeader(gauges) + '\n';
    }
    ~ProbeFile() {
        if (!m_tmp.empty()) {
            std::error_code ec;
            std::filesystem::remove(m_tmp, ec);
        }
    }
    bool enabled() const { return !m_path.empty(); }
    void add(const std::string& row) { m_text += row + '\n'; }
    /// Writes the temporary file (before the cache is renamed into place, so a failure here
    /// leaves neither new file).
    void write() {
        if (!enabled())
            return;
        m_tmp = cache::temporaryPath(m_path);
        if (const int err = cache::writeFile(m_tmp, m_text.data(), m_text.size()); err != 0)
            fail(err, "; no cache written");
    }
    /// Renames it into place (after the cache).
    void commit() {
        if (!enabled())
            return;
        if (std::rename(m_tmp.c_str(), m_path.c_str()) != 0)
            fail(errno, "");
        m_tmp.clear();
    }

private:
    [[noreturn]] void fail(int err, const char* also) const {
        throw std::runtime_error(fmt::format("cannot write probes file {}: {}{}", m_path.string(),
                                             std::strerror(err), also));
    }
    std::filesystem::path m_path, m_tmp;
    std::string m_text;
};

/// Paper Sec. 3.3.2, particle recycling (Algorithm 1 step 8, "Delete particles", and step 3,
/// "Add particles"): water past the outflow re-enters at the inflow, at the lowest free
/// lattice slot of the column next to the back wall (up to the still-water level), with the
/// inflow velocity. A slot is free when no water particle lies within 0.9 l0 of it. Water
/// that finds no free slot waits beyond the outflow (the basin in front of the front wall)
/// and is tried again next step, so the particle count is always conserved.
std::size_t recycle(MpsSolver& solver, const Scene& scene) {
    const RecyclingParams& r = *scene.recycling;
    const Particles& P = solver.particles();
    const double l0 = scene.geometry.particleSpacing;
    const Box& tank = *scene.geometry.tank;
    const double slotX = tank.x0 + 0.5 * l0;
    std::vector<std::size_t> leaving;
    std::vector<double> nearY; // heights of water near the slot column
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] != ParticleKind::Water)
            continue;
        if (P.x[i] > r.outflowX) {
            leaving.push_back(i);
        } else if (std::abs(P.x[i] - slotX) < 0.9 * l0) {
            nearY.push_back(P.y[i]);
        }
    }
    if (leaving.empty())
        return 0;
    const long rows = std::lround((stillWaterLevel(scene) - tank.y0) / l0);
    std::size_t moved = 0;
    for (long j = 0; j < rows && moved < leaving.size(); ++j) {
        const double y = tank.y0 + (static_cast<double>(j) + 0.5) * l0;
        bool free = true;
        for (std::size_t k = 0; k < nearY.size() && free; ++k) {
            // distance in x is below 0.9 l0 for every particle of nearY; check the full distance
            free = std::abs(nearY[k] - y) >= 0.9 * l0;
        }
        if (!free)
            continue;
        const std::size_t i = leaving[moved++];
        solver.relocateWater(i, slotX, y, r.velocity, 0.0);
        nearY.push_back(y);
    }
    return moved;
}

/// Water gone over the tank's walls leaves the run (spill.h); returns how many particles went.
/// Water found outside the tank lower than a wall's top went through a solid: the bake stops
/// there, as at any other divergence.
std::size_t removeSpilledWater(MpsSolver& solver, const TankOutline& tank) {
    const std::vector<EscapedWater> escaped = findEscapedWater(solver.particles(), tank);
    if (escaped.empty())
        return 0;
    const Particles& P = solver.particles();
    std::vector<std::size_t> gone;
    for (const EscapedWater& e : escaped) {
        const std::size_t i = e.particle;
        if (!spilled(e.route)) {
            const Box& t = tank.inner;
            throw DivergenceError(
                solver.stepCount(), solver.time(), i,
                fmt::format("water particle at ({:.6g}, {:.6g}) m, velocity ({:.4g}, {:.4g}) m/s, "
                            "went {} of the tank [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] m",
                            P.x[i], P.y[i], P.vx[i], P.vy[i], toString(e.route), t.x0, t.x1, t.y0,
                            t.y1));
        }
        gone.push_back(i);
    }
    if (gone.size() >= P.count(ParticleKind::Water)) {
        throw DivergenceError(solver.stepCount(), solver.time(), gone.front(),
                              "all the water has gone over the tank's walls");
    }
    solver.removeWater(gone);
    return gone.size();
}

/// Water that starts outside the tank (beyond its walls or bed) would be taken for water gone
/// over or through them: a SceneError naming the water rectangle instead.
void requireWaterInTank(const Particles& P, const GeometryParams& g, const TankOutline& tank) {
    const std::vector<EscapedWater> outside = findEscapedWater(P, tank);
    if (outside.empty())
        return;
    const std::size_t i = outside.front().particle;
    std::string key = "geometry.water";
    for (std::size_t w = 0; w < g.water.size(); ++w) {
        const Box& b = g.water[w];
        const double m = g.particleSpacing; // the jitter moves particles by less
        if (Box{b.x0 - m, b.y0 - m, b.x1 + m, b.y1 + m}.contains(P.x[i], P.y[i])) {
            key = fmt::format("geometry.water[{}]", w);
            break;
        }
    }
    const Box o = tank.outer();
    throw SceneError(key, fmt::format("water at ({:.6g}, {:.6g}) m starts outside the tank: beyond "
                                      "its walls ({:.6g} to {:.6g} m with the wall layers) or "
                                      "below its bed ({:.6g} m)",
                                      P.x[i], P.y[i], o.x0, o.x1, o.y0));
}

/// A bake killed with SIGKILL leaves its temporary cache (CACHE.tmp-<pid>), maybe a
/// half-written checkpoint (CACHE.ckpt.tmp-<pid>) and probes file (PROBES.tmp-<pid>) behind;
/// remove those of processes that are gone, never those of a live one. Called with the
/// output's lock held, so no other swell-bake is writing them.
void removeStaleTemporaries(const std::filesystem::path& output,
                            const std::filesystem::path& probes) {
    namespace fs = std::filesystem;
    std::vector<fs::path> stale;
    for (const fs::path& file : {output, checkpointPath(output), probes}) {
        if (file.empty())
            continue;
        const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
        const std::string prefix = file.filename().string() + ".tmp-";
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(dir, ec)) {
            const std::string f = e.path().filename().string();
            if (f.compare(0, prefix.size(), prefix) != 0 || f.size() == prefix.size())
                continue;
            const long pid = cache::temporaryFileWriter(e.path());
            if (pid > 0 && pid != ::getpid() &&
                f.size() == prefix.size() + std::to_string(pid).size() &&
                !cache::processExists(pid))
                stale.push_back(e.path());
        }
    }
    for (const fs::path& p : stale) {
        std::error_code ec;
        fs::remove(p, ec);
    }
}

/// The height potential energy is measured from: the tank's bed, or without a tank the lowest
/// water.
double energyDatum(const Scene& scene, const Particles& P) {
    double bed =
        scene.geometry.tank ? scene.geometry.tank->y0 : std::numeric_limits<double>::infinity();
    if (!scene.geometry.tank) {
        for (std::size_t i = 0; i < P.size(); ++i) {
            if (P.kind[i] == ParticleKind::Water)
                bed = std::min(bed, P.y[i]);
        }
    }
    return bed;
}

/// Header: everything needed to reproduce the bake (docs/cache-format.md).
cache::Header cacheHeader(const Scene& scene, const BakeOptions& opt, const Box& dom,
                          const BakeSummary& sum, long steps, long interval, double n0) {
    cache::Header header;
    header.domain = cache::Domain{static_cast<float>(dom.x0), static_cast<float>(dom.y0),
                                  static_cast<float>(dom.x1), static_cast<float>(dom.y1)};
    header.dt = scene.solver.time.dt;
    header.frameInterval = static_cast<std::uint32_t>(interval);
    header.seed = scene.seed;
    const json meta{
        {"program", "swell-bake"},
        {"version", opt.programVersion},
        {"numerics_version", kNumericsVersion},
        {"scene_file", opt.sceneFile},
        {"overrides", opt.overrides},
        {"scene", toJson(scene)},
        {"seed", scene.seed},
        {"dt", scene.solver.time.dt},
        {"steps", steps},
        {"frame_interval_steps", interval},
        {"n0", n0},
        {"still_water_level", stillWaterLevel(scene)},
        {"particles_water", sum.particlesWater},
        {"particles_wall", sum.particlesWall},
        // What the runtime cannot guess: water extent and steady start (replay_window.h).
        {"replay", toJson(sum.replay)}};
    header.metadataJson = meta.dump();
    return header;
}

/// Checkpoints (docs/scenes.md "Checkpoints"): a resume must match what decides the
/// numbers: the numerics version, the scene and the overrides; not the thread count
/// (numerics_version.h), the program version or build (a rebuild keeps a long bake).
/// "threads": "any" is what builds before the thread count stopped mattering wrote for
/// small scenes, so their checkpoints still resume; their large-scene checkpoints, which
/// name a count, are refused.
std::string checkpointFingerprint(const Scene& scene, const BakeOptions& opt) {
    return json{{"numerics_version", kNumericsVersion},
                {"scene", toJson(scene)},
                {"overrides", opt.overrides},
                {"threads", "any"}}
        .dump();
}

/// Reads the checkpoint at ckptPath, checks that it belongs to this bake (its fingerprint, its
/// step and stored frames) and imports its solver state.
Checkpoint resumeCheckpoint(const std::filesystem::path& ckptPath, const std::string& fingerprint,
                            long steps, long interval, MpsSolver& solver) {
    Checkpoint resumed = readCheckpoint(ckptPath);
    checkFingerprint(ckptPath, resumed.fingerprint, fingerprint);
    const long first = resumed.solver.step;
    if (first < 1 || first > steps ||
        resumed.frames.size() != static_cast<std::size_t>(first / interval + 1)) {
        throw CheckpointError(
            fmt::format("{}: damaged checkpoint: step {} with {} stored frames does not fit "
                        "this bake ({} steps, a frame every {})",
                        ckptPath.string(), first, resumed.frames.size(), steps, interval));
    }
    try {
        solver.importState(resumed.solver);
    } catch (const std::invalid_argument& e) {
        throw CheckpointError(
            fmt::format("{}: checkpoint does not fit the scene: {}", ckptPath.string(), e.what()));
    }
    return resumed;
}

/// A bake's steps and what they leave: the stored frames (in the cache, the probes file and,
/// with checkpoints, the frames and probe rows a checkpoint holds), the checkpoints and the
/// totals.
struct BakeSteps {
    const Scene& scene;
    const BakeOptions& opt;
    MpsSolver& solver;
    const std::optional<TankOutline>& outline;
    cache::Writer& writer;
    ProbeFile& probes;
    const ProbeParams& probeParams;
    const std::filesystem::path& ckptPath;
    const std::string& fingerprint;
    long every; ///< steps between checkpoints; 0: none
    double n0;
    BakeTotals& tot;
    BakeSummary& sum;
    // With checkpoints the stored frames and probe rows are kept: a checkpoint holds them all.
    std::vector<cache::Frame> keptFrames = {};
    std::vector<std::string> keptRows = {};

    bool keep() const { return every > 0; }

    /// Stored frame: eq. (4) classification, only surface and splash particles kept (Sec. 3.2).
    void store() {
        const Particles& P = solver.particles();
        const double d1 = scene.output.splashRatio, d2 = scene.output.surfaceRatio;
        ClassifiedFrame c = classifyParticles(P, n0, d1, d2, solver.surfaceLayer());
        writer.addFrame(c.frame);
        tot.surface += static_cast<double>(c.surface());
        tot.splash += static_cast<double>(c.splash());
        tot.keptMax = std::max<std::uint64_t>(tot.keptMax, c.surface() + c.splash());
        tot.rawBytes += (c.frame.surface.size() + c.frame.splash.size()) * sizeof(float);
        if (probes.enabled() || keep()) {
            std::string row = probeCsvRow(sampleProbes(P, solver.time(), probeParams));
            if (probes.enabled())
                probes.add(row);
            if (keep())
                keptRows.push_back(std::move(row));
        }
        if (keep())
            keptFrames.push_back(std::move(c.frame));
    }

    /// Writes a checkpoint: the solver's state, the frames and probe rows so far, the totals.
    void saveCheckpoint() {
        const auto t0 = Clock::now();
        Checkpoint ck;
        ck.fingerprint = fingerprint;
        ck.checkpointEvery = every;
        ck.solver = solver.exportState();
        ck.frames = std::move(keptFrames); // lent to the checkpoint, taken back below
        ck.probeRows = std::move(keptRows);
        ck.totals = tot;
        ck.writerPid = ::getpid();
        sum.checkpointBytes = writeCheckpoint(ckptPath, ck);
        keptFrames = std::move(ck.frames);
        keptRows = std::move(ck.probeRows);
        ++sum.checkpoints;
        sum.checkpointSeconds += secondsSince(t0);
    }

    /// The frames stored before the checkpoint, re-encoded exactly as the first run did.
    void restore(Checkpoint& resumed) {
        for (std::size_t f = 0; f < resumed.frames.size(); ++f) {
            writer.addFrame(resumed.frames[f]);
            if (probes.enabled())
                probes.add(resumed.probeRows[f]);
        }
        if (keep()) {
            keptFrames = std::move(resumed.frames);
            keptRows = std::move(resumed.probeRows);
        }
    }

    /// The frames before the first step: those of the checkpoint resumed from (let go once
    /// stored), or else frame 0.
    void storeFirstFrames(std::optional<Checkpoint>& resumed) {
        if (resumed) {
            restore(*resumed);
            resumed.reset();
        } else {
            store(); // frame 0: the initial state
        }
    }

    /// One solver step, then recycling and the water gone over the walls; adds it to the totals.
    void step() {
        const StepStats& st = solver.step();
        if (scene.recycling)
            tot.recycled += recycle(solver, scene);
        if (outline) {
            if (const std::size_t gone = removeSpilledWater(solver, *outline); gone > 0) {
                if (tot.spilled == 0)
                    tot.firstSpillTime = solver.time();
                tot.spilled += gone;
            }
        }
        tot.solverSeconds += st.seconds();
        tot.ppeIterations += st.ppeIterations;
        tot.maxCourant = std::max(tot.maxCourant, st.courant);
        if (st.substeps > 1) {
            ++tot.splitSteps;
            tot.substeps += static_cast<std::uint64_t>(st.substeps);
        }
    }

    /// Stops the bake cancelled after step k, saving a checkpoint first where it takes them.
    [[noreturn]] void cancel(long k) {
        if (every > 0) {
            saveCheckpoint();
            throw BakeCancelled(fmt::format("bake cancelled at step {} (t = {:.4f} s); no cache "
                                            "written; checkpoint {} saved: continue with --resume",
                                            k, solver.time(), ckptPath.string()));
        }
        throw BakeCancelled(fmt::format(
            "bake cancelled at step {} (t = {:.4f} s); no cache written", k, solver.time()));
    }

    /// Steps first + 1 to steps: a frame stored every `interval`, a checkpoint every `every`.
    void run(long first, long steps, long interval) {
        const auto solveStart = Clock::now();
        for (long k = first + 1; k <= steps; ++k) {
            step();
            if (k % interval == 0)
                store();
            if (opt.onProgress) {
                opt.onProgress(BakeProgress{k, first, steps, solver.time(),
                                            secondsSince(solveStart), writer.frameCount()});
            }
            if (opt.cancelled && opt.cancelled())
                cancel(k);
            if (every > 0 && k % every == 0 && k < steps)
                saveCheckpoint();
        }
    }
};

/// The summary's totals and means over the bake's steps and stored frames (sum.frames), the
/// cache's size, and a warning where water went over the tank's walls.
void summarise(BakeSummary& sum, const BakeTotals& tot, long steps,
               const std::filesystem::path& output) {
    sum.recycled = tot.recycled;
    sum.spilled = tot.spilled;
    if (tot.spilled > 0) {
        sum.warnings.push_back(fmt::format(
            "{} water particle(s) went over the tank's walls and left the run, the first at t = "
            "{:.3f} s (conservation.water_lost counts them; higher walls, geometry.tank.y1, keep "
            "them)",
            tot.spilled, tot.firstSpillTime));
    }
    sum.maxCourant = tot.maxCourant;
    sum.splitSteps = tot.splitSteps;
    sum.substeps = tot.substeps;
    sum.keptMax = static_cast<std::size_t>(tot.keptMax);
    sum.rawBytes = tot.rawBytes;
    const double surfaceTotal = tot.surface, splashTotal = tot.splash;
    const double solverSeconds = tot.solverSeconds, ppeIterations = tot.ppeIterations;
    sum.cacheBytes = std::filesystem::file_size(output);
    sum.surfaceMean = surfaceTotal / static_cast<double>(sum.frames);
    sum.splashMean = splashTotal / static_cast<double>(sum.frames);
    const double kept = sum.surfaceMean + sum.splashMean;
    sum.reduction = kept > 0.0 ? static_cast<double>(sum.particlesWater) / kept : 0.0;
    sum.msPerStep = 1e3 * solverSeconds / static_cast<double>(steps);
    sum.ppeIterationsMean = ppeIterations / static_cast<double>(steps);
}

} // namespace

long frameIntervalSteps(const Scene& scene) {
    if (scene.solver.time.adaptive) {
        throw SceneError("solver.adaptive_dt",
                         "swell-bake needs a fixed time step (stored frames are evenly spaced in "
                         "steps); set it to false");
    }
    const double ratio = scene.output.frameInterval / scene.solver.time.dt;
    const double k = std::round(ratio);
    if (k > 1e9) { // the cache header stores it in 32 bits; the run itself is at most 1e9 steps
        throw SceneError("output.frame_interval",
                         fmt::format("{} s is {:.4g} steps of dt = {} s: must be at most 1e9 steps",
                                     scene.output.frameInterval, k, scene.solver.time.dt));
    }
    if (k < 1.0 || std::abs(ratio - k) > 1e-6 * k) {
        throw SceneError("output.frame_interval",
                         fmt::format("{} s is not a whole number of time steps dt = {} s",
                                     scene.output.frameInterval, scene.solver.time.dt));
    }
    return static_cast<long>(k);
}

long totalSteps(const Scene& scene) {
    const double k = std::round(scene.run.endTime / scene.solver.time.dt);
    if (k < 1.0 || k > 1e9) {
        throw SceneError("solver.end_time",
                         fmt::format("{} s is {} steps of dt = {} s: must be 1 to 1e9",
                                     scene.run.endTime, k, scene.solver.time.dt));
    }
    return static_cast<long>(k);
}

std::vector<std::string> sceneWarnings(const Scene& scene) {
    std::vector<std::string> out;
    // A solitary stroke's height is checked against the depth where the scene is loaded.
    if (!scene.piston || !scene.geometry.tank || scene.piston->kind == PistonKind::Solitary)
        return out;
    const PistonParams& p = *scene.piston;
    const double depth = stillWaterLevel(scene) - scene.geometry.tank->y0;
    if (!(depth > 0.0))
        return out;
    // Linear theory: the piston transfer function H/S and dispersion give H/L; Miche limits it.
    // Random motion: the steepest combination is the largest stroke at the shortest period.
    const bool sinus = p.kind == PistonKind::Sinusoidal;
    const double stroke = sinus ? p.stroke : p.strokeMax;
    const double period = sinus ? p.period : p.periodMin;
    if (!(stroke > 0.0))
        return out;
    const LinearPistonWave w = linearPistonWave(stroke, period, depth, scene.physics.gravity);
    if (w.breaks()) {
        out.push_back(fmt::format(
            "piston wave breaks: linear theory gives H = {:.3g} m, L = {:.3g} m, H/L = {:.3f} "
            "above the Miche limit {:.3f} (kh = {:.2f}, stroke {} m, period {} s{})",
            w.height, w.wavelength, w.steepness, w.breakingSteepness, w.kh, stroke, period,
            sinus ? "" : ", steepest random cycle"));
    }
    return out;
}

Conservation measureConservation(const MpsSolver& solver, const Scene& scene, double bed) {
    const Particles& P = solver.particles();
    const double l0 = scene.geometry.particleSpacing;
    const double n0 = solver.densityConstants().n0;
    const double mass = scene.physics.density * l0 * l0;
    const double g = scene.physics.gravity;
    Conservation c;
    double nSum = 0.0;
    std::size_t interior = 0;
    for (std::size_t i = 0; i < P.size(); ++i) {
        if (P.kind[i] != ParticleKind::Water)
            continue;
        ++c.water;
        if (!scene.geometry.tank || scene.geometry.tank->contains(P.x[i], P.y[i]))
            ++c.inTank;
        if (P.n[i] >= scene.output.surfaceRatio * n0) {
            nSum += P.n[i];
            ++interior;
        }
        c.kineticEnergy += 0.5 * mass * (P.vx[i] * P.vx[i] + P.vy[i] * P.vy[i]);
        c.potentialEnergy += mass * g * (P.y[i] - bed);
    }
    const double nMean = interior ? nSum / static_cast<double>(interior) : n0;
    // Read on the packing kernel where the scheme has one (re_packing): the density kernel
    // reads a hexagonal packing as denser than a square one of the same area, by the packing
    // factor the solver aims its density term at (MpsSolver::packingFactor, 1 without).
    c.volume = static_cast<double>(c.water) * l0 * l0 * (nMean > 0.0 ? n0 / nMean : 1.0) *
               solver.packingFactor();
    return c;
}

namespace {
json conservationJson(const Conservation& c) {
    return json{{"water", c.water},
                {"in_tank", c.inTank},
                {"volume", c.volume},
                {"kinetic_energy", c.kineticEnergy},
                {"potential_energy", c.potentialEnergy},
                {"energy", c.kineticEnergy + c.potentialEnergy}};
}
} // namespace

json toJson(const BakeSummary& s) {
    const double e0 = s.start.kineticEnergy + s.start.potentialEnergy;
    const double e1 = s.end.kineticEnergy + s.end.potentialEnergy;
    return json{
        {"conservation",
         {{"start", conservationJson(s.start)},
          {"end", conservationJson(s.end)},
          {"water_lost",
           static_cast<long long>(s.start.water) - static_cast<long long>(s.end.water)},
          {"volume_change", s.start.volume > 0.0 ? s.end.volume / s.start.volume - 1.0 : 0.0},
          {"energy_drift", e0 > 0.0 ? e1 / e0 - 1.0 : 0.0}}},
        {"particles_water", s.particlesWater},
        {"particles_wall", s.particlesWall},
        {"steps", s.steps},
        {"frame_interval_steps", s.frameIntervalSteps},
        {"frames", s.frames},
        {"surface_mean", s.surfaceMean},
        {"splash_mean", s.splashMean},
        {"kept_mean", s.surfaceMean + s.splashMean},
        {"kept_max", s.keptMax},
        {"reduction", s.reduction},
        {"wall_seconds", s.wallSeconds},
        {"ms_per_step", s.msPerStep},
        {"ppe_iterations_mean", s.ppeIterationsMean},
        {"max_courant", s.maxCourant},
        {"split_steps", s.splitSteps},
        {"substeps", s.substeps},
        {"recycled", s.recycled},
        {"spilled", s.spilled},
        {"cache_bytes", s.cacheBytes},
        {"raw_bytes", s.rawBytes},
        {"resumed_from_step", s.resumedFromStep},
        {"checkpoints", s.checkpoints},
        {"checkpoint_bytes", s.checkpointBytes},
        {"checkpoint_seconds", s.checkpointSeconds},
        {"compression_ratio", s.cacheBytes ? static_cast<double>(s.rawBytes) / s.cacheBytes : 0.0},
        {"replay", toJson(s.replay)},
        {"warnings", s.warnings}};
}

BakeSummary runBake(const Scene& scene, const BakeOptions& opt) {
    const auto start = Clock::now();
    const long interval = frameIntervalSteps(scene);
    const long steps = totalSteps(scene);
    BakeSummary sum;
    sum.steps = steps;
    sum.frameIntervalSteps = interval;
    sum.warnings = sceneWarnings(scene);
    sum.replay = replayWindow(scene);

    MpsSolver solver = makeSolver(scene);
    const Particles& P = solver.particles();
    const std::optional<TankOutline> outline =
        scene.geometry.tank ? std::optional(tankOutline(scene.geometry)) : std::nullopt;
    if (outline)
        requireWaterInTank(P, scene.geometry, *outline);
    // Conservation at the start: the scene's initial state (also when resuming, before the
    // checkpoint's state is imported below).
    const double bed = energyDatum(scene, P);
    sum.start = measureConservation(solver, scene, bed);
    sum.particlesWater = P.count(ParticleKind::Water);
    sum.particlesWall = P.size() - sum.particlesWater;
    const double n0 = solver.densityConstants().n0;
    const cache::Header header = cacheHeader(scene, opt, solver.domain(), sum, steps, interval, n0);

    // One writer per output (cache, checkpoint, temporaries), from before the checkpoint is
    // read until the cache is complete; then the leftovers of killed bakes can go.
    const cache::OutputLock lock(opt.output);
    removeStaleTemporaries(opt.output, opt.probes);

    const std::filesystem::path ckptPath = checkpointPath(opt.output);
    const std::string fingerprint = checkpointFingerprint(scene, opt);
    std::optional<Checkpoint> resumed;
    long first = 0; // steps already done
    BakeTotals tot;
    if (opt.resume) {
        resumed = resumeCheckpoint(ckptPath, fingerprint, steps, interval, solver);
        first = resumed->solver.step;
        tot = resumed->totals;
        sum.resumedFromStep = first;
    }
    const long every =
        opt.checkpointEvery > 0 ? opt.checkpointEvery : (resumed ? resumed->checkpointEvery : 0);
    // A fresh bake that takes checkpoints would replace the one there, and a failure of the
    // fresh bake would then lose it: refused before anything is written.
    if (!resumed && every > 0 && std::filesystem::exists(ckptPath)) {
        throw CheckpointError(fmt::format(
            "{}: a checkpoint of an earlier bake is there, and a fresh bake with "
            "--checkpoint-every would replace it: continue it with --resume, or remove the file "
            "to start afresh",
            ckptPath.string()));
    }

    cache::Writer writer(opt.output, header);
    ProbeFile probes(opt.probes, scene.output.gauges);
    const ProbeParams probeParams =
        probeParamsFor(solver, scene, stillWaterLevel(scene), scene.output.gauges);
    BakeSteps loop{.scene = scene,
                   .opt = opt,
                   .solver = solver,
                   .outline = outline,
                   .writer = writer,
                   .probes = probes,
                   .probeParams = probeParams,
                   .ckptPath = ckptPath,
                   .fingerprint = fingerprint,
                   .every = every,
                   .n0 = n0,
                   .tot = tot,
                   .sum = sum};
    loop.storeFirstFrames(resumed);
    loop.run(first, steps, interval);
    sum.end = measureConservation(solver, scene, bed);
    sum.frames = writer.frameCount();
    probes.write();
    writer.finish();
    probes.commit();
    if (every > 0 || opt.resume) {
        std::error_code ec;
        std::filesystem::remove(ckptPath, ec); // the cache is complete: nothing left to resume
    }
    summarise(sum, tot, steps, opt.output);
    sum.wallSeconds = secondsSince(start);
    return sum;
}

} // namespace swell::bake
