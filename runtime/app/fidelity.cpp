// swell-play fidelity: the replay against the simulated surface it replays (docs/runtime.md,
// "Fidelity"): at F = 0, at the given F, and the continuity of a long replay.

#include "command.h"
#include "play_common.h"

#include "swell/cache/synthetic.h"
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/modes/mode_replay.h"
#include "swell/runtime/replay/fidelity.h"
#include "swell/runtime/replay/surface_envelope.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <map>
#include <optional>

namespace swell::play {
namespace {

using namespace swell::runtime;

/// The travelling wave of a `swell-cache synth` cache, read back from its metadata.
std::optional<cache::SyntheticWave> syntheticWave(const cache::Header& header) {
    const json meta = json::parse(header.metadataJson, nullptr, false);
    if (!meta.is_object() || meta.value("generator", "") != "swell-cache synth")
        return std::nullopt;
    cache::SyntheticWave w;
    w.length = meta.value("length_m", w.length);
    w.depth = meta.value("depth_m", w.depth);
    w.amplitude = meta.value("amplitude_m", w.amplitude);
    w.wavelength = meta.value("wavelength_m", w.wavelength);
    w.period = meta.value("period_s", w.period);
    w.frameTime = header.frameTime();
    return w;
}

std::vector<double> row(const HeightField& h, int m) {
    const auto first = h.heights.begin() + static_cast<std::ptrdiff_t>(m) * h.cellsX;
    return {first, first + h.cellsX};
}

double maxChange(const HeightField& a, const HeightField& b) {
    double d = 0.0;
    for (std::size_t i = 0; i < a.heights.size(); ++i)
        d = std::max(d, std::abs(a.heights[i] - b.heights[i]));
    return d;
}

/// The frames' envelopes, made once each.
struct Truths {
    double binWidth = 0.0;
    std::map<std::uint32_t, SurfaceEnvelope> envelopes;
    const SurfaceEnvelope& of(const FrameSet& set, std::uint32_t id) {
        auto it = envelopes.find(id);
        if (it == envelopes.end())
            it = envelopes.emplace(id, SurfaceEnvelope(*set.find(id), binWidth)).first;
        return it->second;
    }
};

/// Fraction of the grid's column centres between the envelope's first and last point (half a
/// bin beyond them): the columns over water.
double overWater(const Grid& grid, const SurfaceEnvelope& env, double binWidth) {
    int over = 0;
    for (int n = 0; n < grid.cellsX && !env.empty(); ++n) {
        const double x = grid.x0 + (n + 0.5) * grid.dx;
        over += x >= env.xFirst() - 0.5 * binWidth && x <= env.xLast() + 0.5 * binWidth;
    }
    return static_cast<double>(over) / grid.cellsX;
}

struct F0Result {
    FidelityStats envelope, analytic;
    bool hasAnalytic = false;
    double spread = 0.0; ///< mean height spread of the measured frames' rows (m)
    double overWaterMean = 0.0, overWaterMin = 1.0;
    Grid grid;
    double l0 = 0.0, step = 0.0, binWidth = 0.0;
};

class FidelityCommand : public Command {
public:
    CLI::App* add(CLI::App& app) override {
        CLI::App* cmd =
            addSubcommand(app, "fidelity",
                          "measure the replay against the simulated surface (F = 0 and F > 0) and "
                          "the continuity of a long replay",
                          m_o);
        cmd->add_option("--frames", m_frames,
                        "F = 0 part: window frames measured, evenly spread (0: every one)")
            ->capture_default_str()
            ->check(CLI::Range(0, 10000000));
        cmd->add_option("--mix-times", m_mixTimes, "F > 0 part: animation times measured (0: skip)")
            ->capture_default_str()
            ->check(CLI::Range(0, 100000));
        cmd->add_option("--seam-seconds", m_seamSeconds,
                        "continuity part: simulated seconds of replay checked for flat rows and "
                        "jumps (0: skip)")
            ->capture_default_str()
            ->check(CLI::Range(0.0, 1.0e6));
        return cmd;
    }

    void check() override {
        finishOptions(m_o);
        if (m_o.modeParams.mode != ReplayMode::Surging)
            throw std::invalid_argument("fidelity measures the surging layout (--mode surging)");
        if (m_seamSeconds > 0.0)
            checkSeconds(m_seamSeconds, m_o.playbackFps, "--seam-seconds");
    }

    int run() override {
        const cache::Reader reader(m_o.cache);
        resolveFromCache(m_o, reader.header());
        const EglContext context;
        m_o0 = m_o; // every slice one frame: F = 0, the window's frames in order
        m_o0.params.fluctuation = 0.0;
        m_o0.params.policy = FramePolicy::Clamp;
        m_o0.policy = "clamp";
        m_plan0 = planTimeline(reader.header(), reader.frameCount(), m_o0.params,
                               [&](std::uint32_t id) { return reader.readFrame(id); });
        const F0Result f0 = measureF0(reader);
        m_plan = planReplay(m_o, reader); // the replay's own timeline, planned once
        const std::vector<double> mixTaus = mixingTaus(reader);
        const ReplaySetup setup = replayOn(m_o, reader, m_plan, mixTaus);
        const FidelityStats mixing = measureMixing(setup, mixTaus, f0);
        json out = resultJson(f0, mixing);
        if (m_seamSeconds > 0.0)
            out["continuity"] = measureContinuity(reader);
        out.update(paramsJson(m_o, setup));
        out["renderer"] = context.renderer();
        if (m_o.json)
            std::cout << out.dump() << "\n";
        else
            print(out, f0, mixing, setup);
        return 0;
    }

private:
    /// F = 0 over `--frames` window frames: the middle row against the frame's envelope (and
    /// the analytic wave of a synthetic cache), spread and columns over water.
    F0Result measureF0(const cache::Reader& reader) const {
        const std::size_t window = m_plan0.timeline.size();
        const std::size_t measured =
            m_frames > 0 ? std::min<std::size_t>(window, static_cast<std::size_t>(m_frames))
                         : window;
        const double A = framesPerTimeUnit(reader.header(), m_o0.params);
        std::vector<double> taus(measured);
        for (std::size_t i = 0; i < measured; ++i) // s = floor(k + 1/2) = k: window frame k
            taus[i] = static_cast<double>(measured > 1 ? i * (window - 1) / (measured - 1) : 0) / A;
        const ReplaySetup s0 = replayOn(m_o0, reader, m_plan0, taus);
        ModeReplay gpu(s0.set, m_o0.params, m_o0.modeParams, s0.samplers);
        F0Result r;
        r.grid = gpu.grid();
        r.l0 = m_plan0.record.particleSpacing;
        r.step = (r.l0 > 0.0 ? r.l0 : r.grid.dx) / 4.0;
        Truths truth{envelopeBinWidth(reader.header(), r.grid), {}};
        r.binWidth = truth.binWidth;
        const std::optional<cache::SyntheticWave> wave = syntheticWave(reader.header());
        r.hasAnalytic = wave.has_value();
        for (double tau : taus) {
            gpu.update(tau);
            const HeightField h = gpu.readHeights();
            const std::uint32_t frame = s0.samplers[0].frame(tau, 0);
            const std::vector<double> mid = row(h, r.grid.cellsZ / 2);
            const SurfaceEnvelope& env = truth.of(s0.set, frame);
            r.envelope.add(compareRow(mid, r.grid, env, r.step));
            r.spread += rowSpread(h, r.grid.cellsZ / 2);
            const double fraction = overWater(r.grid, env, truth.binWidth);
            r.overWaterMean += fraction;
            r.overWaterMin = std::min(r.overWaterMin, fraction);
            if (wave) {
                const double t = frame * reader.header().frameTime();
                r.analytic.add(compareRow(
                    mid, r.grid, [&](double x) { return cache::syntheticHeight(*wave, x, t); }, 0.0,
                    wave->length, r.step));
            }
        }
        const double n = std::max<double>(1.0, static_cast<double>(taus.size()));
        r.spread /= n;
        r.overWaterMean /= n;
        return r;
    }

    /// `--mix-times` animation times evenly over one period of the replay's timeline.
    std::vector<double> mixingTaus(const cache::Reader& reader) const {
        const double period = static_cast<double>(m_plan.timeline.size()) /
                              framesPerTimeUnit(reader.header(), m_o.params);
        std::vector<double> taus(static_cast<std::size_t>(m_mixTimes));
        for (std::size_t i = 0; i < taus.size(); ++i) {
            taus[i] = m_o.start / m_o.params.timeUnitSeconds +
                      period * static_cast<double>(i) / static_cast<double>(taus.size());
        }
        return taus;
    }

    /// At the given F: each real slice's row against its own frame (the mixing error).
    FidelityStats measureMixing(const ReplaySetup& setup, const std::vector<double>& taus,
                                const F0Result& f0) const {
        FidelityStats mixing;
        if (!(m_o.params.fluctuation > 0.0) || taus.empty())
            return mixing;
        ModeReplay gpu(setup.set, m_o.params, m_o.modeParams, setup.samplers);
        const Grid& grid = f0.grid;
        Truths truth{f0.binWidth, {}};
        for (double tau : taus) {
            gpu.update(tau);
            const HeightField h = gpu.readHeights();
            const std::vector<std::uint32_t> shown = gpu.readSliceFrames()[0];
            for (int j = 0; j < grid.sliceCount(); j += 2) {
                const int m = std::clamp(static_cast<int>(std::floor(grid.sliceZCells(j))), 0,
                                         grid.cellsZ - 1);
                mixing.add(compareRow(row(h, m), grid,
                                      truth.of(setup.set, shown[static_cast<std::size_t>(j)]),
                                      f0.step));
            }
        }
        return mixing;
    }

    /// The largest per-cell change between consecutive output frames of the steady bake at
    /// F = 0, at the same output rate: its 99.9th percentile.
    double steadyChangeP999(const cache::Reader& reader) const {
        const auto n =
            static_cast<std::size_t>(std::floor(static_cast<double>(m_plan0.timeline.size() - 1) *
                                                m_plan0.frameTime * m_o.playbackFps));
        std::vector<double> taus(n + 1);
        for (std::size_t i = 0; i <= n; ++i)
            taus[i] = static_cast<double>(i) / m_o.playbackFps / m_o0.params.timeUnitSeconds;
        const ReplaySetup s = replayOn(m_o0, reader, m_plan0, taus);
        ModeReplay gpu(s.set, m_o0.params, m_o0.modeParams, s.samplers);
        std::vector<double> changes;
        HeightField prev;
        for (std::size_t i = 0; i <= n; ++i) {
            gpu.update(taus[i]);
            HeightField h = gpu.readHeights();
            if (i > 0)
                changes.push_back(maxChange(prev, h));
            prev = std::move(h);
        }
        return changes.empty() ? 0.0 : percentile(changes, 0.999);
    }

    /// `--seam-seconds` of replay: frames with flat rows and the largest per-cell change.
    json measureContinuity(const cache::Reader& reader) const {
        const double p999 = steadyChangeP999(reader);
        const std::vector<double> taus = outputTaus(m_o, m_seamSeconds);
        const ReplaySetup s = replayOn(m_o, reader, m_plan, taus);
        ModeReplay gpu(s.set, m_o.params, m_o.modeParams, s.samplers);
        HeightField prev;
        std::size_t flatFrames = 0, flatRowCount = 0;
        double largest = 0.0, largestAt = 0.0;
        json flatAt = json::array(); // the first 20 times with a flat row
        for (std::size_t i = 0; i < taus.size(); ++i) {
            gpu.update(taus[i]);
            HeightField h = gpu.readHeights();
            const auto flat = static_cast<std::size_t>(flatRows(h));
            flatRowCount += flat;
            flatFrames += flat > 0 ? 1 : 0;
            if (flat > 0 && flatAt.size() < 20)
                flatAt.push_back(secondsOf(m_o, i));
            const double change = i > 0 ? maxChange(prev, h) : 0.0;
            if (change > largest) {
                largest = change;
                largestAt = secondsOf(m_o, i);
            }
            prev = std::move(h);
        }
        return {{"seconds", m_seamSeconds},
                {"frames", taus.size()},
                {"flat_row_threshold_m", kFlatRowMetres},
                {"frames_with_flat_rows", flatFrames},
                {"flat_rows", flatRowCount},
                {"flat_at_s", flatAt},
                {"largest_change_m", largest},
                {"largest_change_at_s", largestAt},
                {"steady_f0_change_p999_m", p999},
                {"largest_over_steady_p999", p999 > 0.0 ? largest / p999 : 0.0}};
    }

    json resultJson(const F0Result& f0, const FidelityStats& mixing) const {
        json out{{"f0", toJson(f0.envelope, f0.l0)},
                 {"mixing", toJson(mixing, f0.l0)},
                 {"steady_spread_m", f0.spread},
                 {"columns_over_water", {{"mean", f0.overWaterMean}, {"min", f0.overWaterMin}}},
                 {"fidelity_definition",
                  "row of the height field, linear between cell centres, against the frame's "
                  "upper envelope of surface particles (bins of l0), sampled every l0/4 over "
                  "the water"}};
        out["mixing"]["times"] = m_mixTimes;
        if (f0.hasAnalytic)
            out["f0_analytic"] = toJson(f0.analytic, f0.l0);
        return out;
    }

    void print(const json& out, const F0Result& f0, const FidelityStats& mixing,
               const ReplaySetup& setup) const {
        const double l0 = f0.l0;
        auto line = [&](const std::string& what, const FidelityStats& s) {
            return fmt::format("  {}: rms {:.3g} m ({:.3f} l0), max {:.3g} m ({:.3f} l0; per-row "
                               "max {:.3f} l0 on average), crest loss {:.2f} % mean, {:.2f} % "
                               "max, {} rows\n",
                               what, s.rms(), l0 > 0 ? s.rms() / l0 : 0.0, s.maxAbs,
                               l0 > 0 ? s.maxAbs / l0 : 0.0, l0 > 0 ? s.meanRowMax() / l0 : 0.0,
                               100.0 * s.meanCrestLoss(), 100.0 * s.maxCrestLoss, s.rows);
        };
        const Grid& g = f0.grid;
        std::cout << fmt::format("swell-play fidelity  {}  ({}x{} cells over x {:.3f} .. {:.3f} "
                                 "m, {} reconstruction, sigma {}, l0 {} m)\n",
                                 m_o.cache, g.cellsX, g.cellsZ, g.x0, g.x0 + g.cellsX * g.dx,
                                 m_o.reconstruction, m_o.params.sigma, l0);
        std::cout << fmt::format("  columns over water (between the frame's first and last "
                                 "surface particle): {:.1f} % on average, {:.1f} % at least\n",
                                 100.0 * f0.overWaterMean, 100.0 * f0.overWaterMin);
        std::cout << line("F = 0 vs the frames' envelopes", f0.envelope);
        if (f0.hasAnalytic)
            std::cout << line("F = 0 vs the analytic wave", f0.analytic);
        if (m_o.params.fluctuation > 0.0 && m_mixTimes > 0)
            std::cout << line(
                fmt::format("F = {} slice rows vs their frames", m_o.params.fluctuation), mixing);
        if (const auto& l = setup.plan.timeline.loop()) {
            std::cout << fmt::format("  loop: frames {} -> {} ({:.2f} s), cross-fade {} frames, "
                                     "residual {:.3g} m (typical frame difference {:.3g} m)\n",
                                     l->in, l->out, (l->out - l->in) * setup.plan.frameTime,
                                     l->crossfade, l->residual, l->typicalDifference);
        }
        if (out.contains("continuity")) {
            const json& c = out["continuity"];
            std::cout << fmt::format(
                "  continuity over {} s at {} fps: {} frames with flat rows ({} rows); largest "
                "per-cell change {:.4f} m at {:.2f} s = {:.2f} x the steady F = 0 99.9th "
                "percentile {:.4f} m\n",
                m_seamSeconds, m_o.playbackFps, c["frames_with_flat_rows"].get<std::size_t>(),
                c["flat_rows"].get<std::size_t>(), c["largest_change_m"].get<double>(),
                c["largest_change_at_s"].get<double>(), c["largest_over_steady_p999"].get<double>(),
                c["steady_f0_change_p999_m"].get<double>());
        }
    }

    Options m_o, m_o0;
    TimelinePlan m_plan0;       ///< F = 0, clamp: the window's frames in order
    TimelinePlan m_plan;        ///< the replay's timeline (policy, loop points)
    int m_frames = 0;           ///< F = 0 part: window frames measured (0: all)
    int m_mixTimes = 24;        ///< F > 0 part: animation times measured
    double m_seamSeconds = 0.0; ///< continuity part: simulated seconds replayed (0: skip)
};

} // namespace

std::unique_ptr<Command> makeFidelityCommand() {
    return std::make_unique<FidelityCommand>();
}

} // namespace swell::play
