// swell-play look: the picture check. Replays the cache at the given options and prints the
// measures a viewer's eye reacts to (picture_measures.h), median over the output frames, each
// beside its target (docs/runtime.md, "Picture check"):
//  * slope ratios (surging, ripple): long crests or stripes along the slices;
//  * needle share: cells more than l0 / 2 above or below all four neighbours;
//  * seeds: the share of cells where the next seed's surface differs by more than l0 / 2;
//  * frame-to-frame change against the bake's own (the same grid replayed at F = 0);
//  * whirlpool: the eye's largest change between consecutive frames against the bake's own;
//  * ripple: the crease ratio where each rotated direction's field ends inside the mesh;
//  * splash sprites (surging, ripple: the render's default splash pass): how many, and how
//    much of the mesh's side one straight row of them covers (frames with 10 or more).

#include "command.h"
#include "play_common.h"

#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/modes/mode_replay.h"
#include "swell/runtime/modes/mode_splashes.h"
#include "swell/runtime/replay/bake_record.h"
#include "swell/runtime/replay/picture_measures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <numbers>
#include <optional>

namespace swell::play {
namespace {

using namespace swell::runtime;

/// Every series measured has at least one value (the guards below).
double median(const std::vector<double>& v) {
    return percentile(v, 0.5);
}

double largest(const std::vector<double>& v) {
    return v.empty() ? NAN : *std::max_element(v.begin(), v.end());
}

/// One measure beside its target: met when lo <= value <= hi.
struct Measured {
    std::string name;
    double value = 0.0;
    double lo = -INFINITY;
    double hi = INFINITY;
    std::string what;

    bool met() const { return value >= lo && value <= hi; }
    json toJson() const {
        return {{"value", value},
                {"min", std::isfinite(lo) ? json(lo) : json(nullptr)},
                {"max", std::isfinite(hi) ? json(hi) : json(nullptr)},
                {"met", met()},
                {"what", what}};
    }
};

/// The height fields of a replay of `o` at `taus`.
std::vector<HeightField> replayFields(const Options& o, const cache::Reader& reader,
                                      const std::vector<double>& taus) {
    const ReplaySetup setup = prepareReplay(o, reader, taus);
    ModeReplay gpu(setup.set, o.params, o.modeParams, setup.samplers);
    std::vector<HeightField> out;
    for (double tau : taus) {
        gpu.update(tau);
        out.push_back(gpu.readHeights());
    }
    return out;
}

/// What look measures per output frame (LookCommand::run), in order.
struct Series {
    std::vector<double> slopeMean, slopeP99, needles, seeds, change, bakeChange, eyeStep, sprites,
        spriteCounts;
    std::vector<std::vector<double>> creases;
};

/// The measures of `m`, each beside its target for `mode`.
std::vector<Measured> measuresOf(const Series& m, ReplayMode mode) {
    std::vector<Measured> measures;
    if (mode != ReplayMode::Whirlpool) {
        const bool surging = mode == ReplayMode::Surging;
        measures.push_back({"slope_ratio_mean", median(m.slopeMean), surging ? 0.15 : -INFINITY,
                            surging ? 0.6 : INFINITY,
                            "mean |dh/dz| / mean |dh/dx| (long crests: 0.15 - 0.6)"});
        measures.push_back({"slope_ratio_p99", median(m.slopeP99), -INFINITY,
                            surging ? 1.0 : INFINITY,
                            "99th percentile of |dh/dz| / that of |dh/dx|"});
    }
    measures.push_back({"needle_share", median(m.needles), -INFINITY, 0.001,
                        "share of cells more than l0/2 above or below all four neighbours"});
    measures.push_back({"needle_share_max", largest(m.needles), -INFINITY, INFINITY,
                        "the same in the worst frame"});
    measures.push_back({"seed_difference", median(m.seeds),
                        mode == ReplayMode::Surging ? 0.1 : -INFINITY, INFINITY,
                        "share of cells where seed + 1 differs by more than l0/2"});
    if (!m.change.empty()) {
        measures.push_back({"frame_change_ratio", median(m.change) / median(m.bakeChange),
                            -INFINITY, INFINITY,
                            "mean frame-to-frame change / the bake's own (F = 0)"});
    }
    if (!m.eyeStep.empty()) {
        measures.push_back({"eye_step_ratio", largest(m.eyeStep) / median(m.bakeChange), -INFINITY,
                            1.0,
                            "largest frame-to-frame change of the eye's mean height / the "
                            "bake's own mean change"});
    }
    for (std::size_t k = 0; k < m.creases.size(); ++k) {
        measures.push_back({fmt::format("crease_ratio_{}", k), median(m.creases[k]), -INFINITY,
                            1.25,
                            "|second difference| across a rotated direction's field end / "
                            "3-8 cells beside it"});
    }
    if (!m.spriteCounts.empty()) {
        measures.push_back({"sprites", median(m.spriteCounts), -INFINITY, INFINITY,
                            "splash sprites per frame (the render's splash pass)"});
    }
    if (!m.sprites.empty()) {
        measures.push_back({"sprite_line_coverage", median(m.sprites), -INFINITY,
                            mode == ReplayMode::Ripple ? 0.25 : INFINITY,
                            "share of the mesh's side that one straight row of splash "
                            "sprites covers"});
    }
    return measures;
}

class LookCommand : public Command {
public:
    CLI::App* add(CLI::App& app) override {
        CLI::App* cmd = addSubcommand(
            app, "look",
            "picture check: slope ratios, needle cells, seed and frame-to-frame "
            "change, the whirlpool's eye, the ripple's creases and sprite lines, each "
            "beside its target",
            m_o);
        cmd->add_option("--seconds", m_seconds, "simulated seconds to measure")
            ->capture_default_str();
        return cmd;
    }

    void check() override {
        finishOptions(m_o);
        checkSeconds(m_seconds, m_o.playbackFps);
    }

    int run() override {
        const cache::Reader reader(m_o.cache);
        resolveFromCache(m_o, reader.header());
        const std::vector<double> taus = outputTaus(m_o, m_seconds);
        const EglContext context;
        const ReplaySetup setup = prepareReplay(m_o, reader, taus);
        ModeReplay gpu(setup.set, m_o.params, m_o.modeParams, setup.samplers);
        const Grid grid = gpu.grid();
        const double l0 = setup.plan.record.particleSpacing > 0.0
                              ? setup.plan.record.particleSpacing
                              : grid.dx; // unknown spacing: one cell
        const double threshold = 0.5 * l0;
        const ReplayMode mode = m_o.modeParams.mode;

        // The other replays on the same grid: the next seed, and the bake itself (F = 0).
        Options next = m_o;
        next.params.seed = m_o.params.seed + 1;
        const std::vector<HeightField> other = replayFields(next, reader, taus);
        Options bake = m_o;
        bake.params.fluctuation = 0.0;
        bake.modeParams.mode = ReplayMode::Surging;
        const std::vector<HeightField> baked = replayFields(bake, reader, taus);

        std::vector<SplashSystem> systems;
        if (mode != ReplayMode::Whirlpool)
            systems = makeSplashSystems(
                setup.set, grid, keepSprayAwayFromTheWaveMaker(SplashParams{}, setup.plan.record),
                m_o.params.seed, setup.samplers.size());

        Series m;
        std::vector<std::vector<double>>& creases = m.creases;
        std::optional<HeightField> previous;
        std::optional<double> previousEye;
        const std::vector<std::array<double, 4>> lines = creaseLines(grid);
        creases.resize(lines.size());
        for (std::size_t i = 0; i < taus.size(); ++i) {
            gpu.update(taus[i]);
            const HeightField h = gpu.readHeights();
            if (mode != ReplayMode::Whirlpool) {
                const SlopeRatios r = slopeRatios(h);
                m.slopeMean.push_back(r.mean);
                m.slopeP99.push_back(r.p99);
            }
            m.needles.push_back(needleShare(h, threshold));
            m.seeds.push_back(shareDiffering(h, other[i], threshold));
            if (previous) {
                m.change.push_back(meanChange(h, *previous));
                m.bakeChange.push_back(meanChange(baked[i], baked[i - 1]));
            }
            if (mode == ReplayMode::Whirlpool) {
                const double radius = 0.5 * m_o.modeParams.whirlpool.innerRadiusCells;
                const double eye = discMean(h, 0.5 * grid.cellsX, 0.5 * grid.extentZ / grid.dz,
                                            radius * grid.dx / grid.dz);
                if (previousEye)
                    m.eyeStep.push_back(std::abs(eye - *previousEye));
                previousEye = eye;
            }
            for (std::size_t k = 0; k < lines.size(); ++k)
                creases[k].push_back(
                    creaseRatio(h, lines[k][0], lines[k][1], lines[k][2], lines[k][3]));
            if (!systems.empty() && systems.front().active()) {
                const std::vector<SplashSprite> s = modeSplashes(
                    systems, setup.samplers, grid, m_o.modeParams, taus[i], secondsOf(m_o, i));
                std::vector<double> xs, zs;
                for (const SplashSprite& p : s) {
                    xs.push_back(p.x);
                    zs.push_back(p.z);
                }
                m.spriteCounts.push_back(static_cast<double>(xs.size()));
                if (xs.size() >= 10)
                    m.sprites.push_back(
                        lineCoverage(xs, zs, SplashParams{}.spawnRadius,
                                     std::max(grid.cellsX * grid.dx, grid.extentZ)));
            }
            previous = h;
        }

        print(measuresOf(m, mode), taus.size(), l0, context.renderer());
        return 0;
    }

private:
    /// Ripple: the lines (point, direction in cells) where each rotated direction's field
    /// ends, those that cross the inner mesh; none in the other modes.
    std::vector<std::array<double, 4>> creaseLines(const Grid& g) const {
        std::vector<std::array<double, 4>> out;
        if (m_o.modeParams.mode != ReplayMode::Ripple)
            return out;
        const double cx = 0.5 * g.cellsX * g.dx, cz = 0.5 * g.extentZ;
        for (double degrees : m_o.modeParams.ripple.anglesDegrees) {
            const double a = degrees * std::numbers::pi / 180.0;
            if (std::abs(std::sin(a)) < 1e-9 && std::cos(a) > 0.0)
                continue; // the unrotated direction covers the mesh
            for (double end : {-0.5, 0.5}) {
                const double px = cx + end * g.cellsX * g.dx * std::cos(a);
                const double pz = cz + end * g.cellsX * g.dx * std::sin(a);
                const double pn = px / g.dx, pm = pz / g.dz;
                const double tn = -std::sin(a) / g.dx, tm = std::cos(a) / g.dz;
                // Keep the line if it passes through the mesh at least 3 cells from its sides.
                bool crosses = false;
                for (double t = -4.0 * g.cellsX; t <= 4.0 * g.cellsX && !crosses; t += 0.5) {
                    const double n = pn + t * tn * g.dx, m = pm + t * tm * g.dx;
                    crosses = n > 3 && n < g.cellsX - 3 && m > 3 && m < g.cellsZ - 3;
                }
                if (crosses)
                    out.push_back({pn, pm, tn, tm});
            }
        }
        return out;
    }

    void print(const std::vector<Measured>& measures, std::size_t frames, double l0,
               const std::string& renderer) const {
        if (m_o.json) {
            json j{{"cache", m_o.cache},   {"mode", m_o.mode},
                   {"preset", m_o.preset}, {"seed", m_o.params.seed},
                   {"frames", frames},     {"seconds", m_seconds},
                   {"l0_m", l0},           {"renderer", renderer}};
            for (const Measured& m : measures)
                j["measures"][m.name] = m.toJson();
            std::cout << j.dump() << "\n";
            return;
        }
        std::cout << fmt::format("swell-play look: {} --mode {} --preset {} --seed {}: {} frames, "
                                 "l0 {:g} m ({})\n",
                                 m_o.cache, m_o.mode, m_o.preset, m_o.params.seed, frames, l0,
                                 renderer);
        for (const Measured& m : measures) {
            std::string target;
            if (std::isfinite(m.lo) && std::isfinite(m.hi))
                target = fmt::format("target {:g} .. {:g}", m.lo, m.hi);
            else if (std::isfinite(m.lo))
                target = fmt::format("target >= {:g}", m.lo);
            else if (std::isfinite(m.hi))
                target = fmt::format("target <= {:g}", m.hi);
            std::cout << fmt::format("  {:<20} {:>9.4f}  {:<22} {}{}\n", m.name, m.value, target,
                                     m.what, target.empty() ? "" : (m.met() ? "" : "  MISSED"));
        }
    }

    Options m_o;
    double m_seconds = 2.0;
};

} // namespace

std::unique_ptr<Command> makeLookCommand() {
    return std::make_unique<LookCommand>();
}

} // namespace swell::play
