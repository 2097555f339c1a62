#include "fidelity.h"

#include "swell/cache/synthetic.h"
#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/replay/fidelity.h"
#include "swell/runtime/modes/mode_replay.h"
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

} // namespace

void addFidelityOptions(CLI::App* cmd, FidelityOptions& f) {
    cmd->add_option("--frames", f.frames,
                    "F = 0 part: window frames measured, evenly spread (0: every one)")
        ->capture_default_str()
        ->check(CLI::Range(0, 10000000));
    cmd->add_option("--mix-times", f.mixTimes, "F > 0 part: animation times measured (0: skip)")
        ->capture_default_str()
        ->check(CLI::Range(0, 100000));
    cmd->add_option("--seam-seconds", f.seamSeconds,
                    "continuity part: simulated seconds of replay checked for flat rows and "
                    "jumps (0: skip)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1.0e6));
}

int runFidelity(Options& o, const FidelityOptions& f) {
    finishOptions(o);
    if (o.modeParams.mode != ReplayMode::Surging)
        throw std::invalid_argument("fidelity measures the surging layout (--mode surging)");
    const cache::Reader reader(o.cache);
    resolveAutoRes(o, reader.header());
    const EglContext context;
    json out;

    // ---- F = 0: every slice shows the same frame; a row is eq. (7)'s profile of that frame.
    Options o0 = o;
    o0.params.fluctuation = 0.0;
    o0.params.policy = FramePolicy::Clamp;
    o0.policy = "clamp";
    const TimelinePlan plan0 = planTimeline(reader.header(), reader.frameCount(), o0.params,
                                            [&](std::uint32_t id) { return reader.readFrame(id); });
    const std::size_t window = plan0.timeline.size();
    const std::size_t measured =
        f.frames > 0 ? std::min<std::size_t>(window, static_cast<std::size_t>(f.frames)) : window;
    const double A = framesPerTimeUnit(reader.header(), o0.params);
    std::vector<double> taus0(measured);
    for (std::size_t i = 0; i < measured; ++i) {
        const std::size_t k = measured > 1 ? i * (window - 1) / (measured - 1) : 0;
        taus0[i] = static_cast<double>(k) / A; // s = floor(k + 1/2) = k: window frame k
    }
    const ReplaySetup s0 = replayOn(o0, reader, plan0, taus0);
    ModeReplay gpu0(s0.set, o0.params, o0.modeParams, s0.samplers);
    const Grid grid = gpu0.grid();
    const BakeRecord& record = plan0.record;
    const double l0 = record.particleSpacing;
    const double step = (l0 > 0.0 ? l0 : grid.dx) / 4.0;
    Truths truth{envelopeBinWidth(reader.header(), grid), {}};
    const std::optional<cache::SyntheticWave> wave = syntheticWave(reader.header());
    FidelityStats f0, analytic;
    double spreadSum = 0.0, overWaterSum = 0.0, overWaterMin = 1.0;
    const int mid = grid.cellsZ / 2;
    for (double tau : taus0) {
        gpu0.update(tau);
        const HeightField h = gpu0.readHeights();
        const std::uint32_t frame = s0.samplers[0].frame(tau, 0);
        const std::vector<double> r = row(h, mid);
        spreadSum += rowSpread(h, mid);
        const SurfaceEnvelope& env = truth.of(s0.set, frame);
        f0.add(compareRow(r, grid, env, step));
        // Columns over water: centres between the frame's first and last surface particle
        // (half a particle spacing beyond them).
        int over = 0;
        for (int n = 0; n < grid.cellsX && !env.empty(); ++n) {
            const double x = grid.x0 + (n + 0.5) * grid.dx;
            over +=
                x >= env.xFirst() - 0.5 * truth.binWidth && x <= env.xLast() + 0.5 * truth.binWidth;
        }
        const double fraction = static_cast<double>(over) / grid.cellsX;
        overWaterSum += fraction;
        overWaterMin = std::min(overWaterMin, fraction);
        if (wave) {
            const double t = frame * reader.header().frameTime();
            analytic.add(compareRow(
                r, grid, [&](double x) { return cache::syntheticHeight(*wave, x, t); }, 0.0,
                wave->length, step));
        }
    }
    out["f0"] = toJson(f0, l0);
    // How much wave the steady bake shows: the mean height spread of its frames' profiles.
    out["steady_spread_m"] = taus0.empty() ? 0.0 : spreadSum / static_cast<double>(taus0.size());
    out["columns_over_water"] = {
        {"mean", taus0.empty() ? 0.0 : overWaterSum / static_cast<double>(taus0.size())},
        {"min", overWaterMin}};
    if (wave)
        out["f0_analytic"] = toJson(analytic, l0);

    // ---- F > 0: each real slice's row against its own frame (the mixing error).
    std::vector<double> taus(static_cast<std::size_t>(f.mixTimes));
    const ReplaySetup probe = prepareReplay(o, reader, {});
    const double period = static_cast<double>(probe.plan.timeline.size()) / probe.A;
    for (std::size_t i = 0; i < taus.size(); ++i)
        taus[i] = o.start / o.params.timeUnitSeconds +
                  period * static_cast<double>(i) / static_cast<double>(taus.size());
    const ReplaySetup setup = prepareReplay(o, reader, taus);
    FidelityStats mixing;
    if (o.params.fluctuation > 0.0 && !taus.empty()) {
        ModeReplay gpu(setup.set, o.params, o.modeParams, setup.samplers);
        Truths mixTruth{truth.binWidth, {}};
        for (double tau : taus) {
            gpu.update(tau);
            const HeightField h = gpu.readHeights();
            const std::vector<std::uint32_t> shown = gpu.readSliceFrames()[0];
            for (int j = 0; j < grid.sliceCount(); j += 2) {
                const int m = std::clamp(static_cast<int>(std::floor(grid.sliceZCells(j))), 0,
                                         grid.cellsZ - 1);
                mixing.add(compareRow(row(h, m), grid,
                                      mixTruth.of(setup.set, shown[static_cast<std::size_t>(j)]),
                                      step));
            }
        }
    }
    out["mixing"] = toJson(mixing, l0);
    out["mixing"]["times"] = taus.size();

    // ---- continuity of a long replay: flat rows and the largest per-cell jump per frame.
    if (f.seamSeconds > 0.0) {
        // The same measure inside the steady bake at F = 0, at the same output rate.
        std::vector<double> steadyChanges;
        {
            const auto n = static_cast<std::size_t>(
                std::floor(static_cast<double>(window - 1) * plan0.frameTime * o.playbackFps));
            std::vector<double> t(n + 1);
            for (std::size_t i = 0; i <= n; ++i)
                t[i] = static_cast<double>(i) / o.playbackFps / o0.params.timeUnitSeconds;
            const ReplaySetup s = replayOn(o0, reader, plan0, t);
            ModeReplay g(s.set, o0.params, o0.modeParams, s.samplers);
            HeightField prev;
            for (std::size_t i = 0; i <= n; ++i) {
                g.update(t[i]);
                HeightField h = g.readHeights();
                if (i > 0)
                    steadyChanges.push_back(maxChange(prev, h));
                prev = std::move(h);
            }
        }
        const double p999 = steadyChanges.empty() ? 0.0 : percentile(steadyChanges, 0.999);
        const std::vector<double> t = outputTaus(o, f.seamSeconds);
        const std::size_t count = t.size();
        const ReplaySetup s = prepareReplay(o, reader, t);
        ModeReplay g(s.set, o.params, o.modeParams, s.samplers);
        HeightField prev;
        std::size_t flatFrames = 0, flatRowCount = 0;
        double largest = 0.0, largestAt = 0.0;
        json flatAt = json::array(); // the first 20 times with a flat row
        for (std::size_t i = 0; i < count; ++i) {
            g.update(t[i]);
            HeightField h = g.readHeights();
            const auto flat = static_cast<std::size_t>(flatRows(h));
            flatRowCount += flat;
            flatFrames += flat > 0 ? 1 : 0;
            if (flat > 0 && flatAt.size() < 20)
                flatAt.push_back(o.start + static_cast<double>(i) / o.playbackFps);
            if (i > 0) {
                const double d = maxChange(prev, h);
                if (d > largest) {
                    largest = d;
                    largestAt = o.start + static_cast<double>(i) / o.playbackFps;
                }
            }
            prev = std::move(h);
        }
        out["continuity"] = {{"seconds", f.seamSeconds},
                             {"frames", count},
                             {"flat_row_threshold_m", kFlatRowMetres},
                             {"frames_with_flat_rows", flatFrames},
                             {"flat_rows", flatRowCount},
                             {"flat_at_s", flatAt},
                             {"largest_change_m", largest},
                             {"largest_change_at_s", largestAt},
                             {"steady_f0_change_p999_m", p999},
                             {"largest_over_steady_p999", p999 > 0.0 ? largest / p999 : 0.0}};
    }

    out.update(paramsJson(o, setup));
    out["renderer"] = context.renderer();
    out["fidelity_definition"] =
        "row of the height field, linear between cell centres, against the frame's upper "
        "envelope of surface particles (bins of l0), sampled every l0/4 over the water";
    if (o.json) {
        std::cout << out.dump() << "\n";
        return 0;
    }
    auto line = [&](const char* what, const FidelityStats& s) {
        return fmt::format(
            "  {}: rms {:.3g} m ({:.3f} l0), max {:.3g} m ({:.3f} l0; per-row max "
            "{:.3f} l0 on average), crest loss {:.2f} % mean, {:.2f} % max, {} rows\n",
            what, s.rms(), l0 > 0 ? s.rms() / l0 : 0.0, s.maxAbs, l0 > 0 ? s.maxAbs / l0 : 0.0,
            l0 > 0 ? s.meanRowMax() / l0 : 0.0, 100.0 * s.meanCrestLoss(), 100.0 * s.maxCrestLoss,
            s.rows);
    };
    std::cout << fmt::format("swell-play fidelity  {}  ({}x{} cells over x {:.3f} .. {:.3f} m, "
                             "{} reconstruction, sigma {}, l0 {} m)\n",
                             o.cache, grid.cellsX, grid.cellsZ, grid.x0,
                             grid.x0 + grid.cellsX * grid.dx, o.reconstruction, o.params.sigma, l0);
    std::cout << fmt::format("  columns over water (between the frame's first and last surface "
                             "particle): {:.1f} % on average, {:.1f} % at least\n",
                             100.0 * out["columns_over_water"]["mean"].get<double>(),
                             100.0 * overWaterMin);
    std::cout << line("F = 0 vs the frames' envelopes", f0);
    if (wave)
        std::cout << line("F = 0 vs the analytic wave", analytic);
    if (o.params.fluctuation > 0.0 && f.mixTimes > 0)
        std::cout << line(
            fmt::format("F = {} slice rows vs their frames", o.params.fluctuation).c_str(), mixing);
    if (const auto& l = setup.plan.timeline.loop()) {
        std::cout << fmt::format("  loop: frames {} -> {} ({:.2f} s), cross-fade {} frames, "
                                 "residual {:.3g} m (typical frame difference {:.3g} m)\n",
                                 l->in, l->out, (l->out - l->in) * setup.plan.frameTime,
                                 l->crossfade, l->residual, l->typicalDifference);
    }
    if (out.contains("continuity")) {
        const json& c = out["continuity"];
        std::cout << fmt::format(
            "  continuity over {} s at {} fps: {} frames with flat rows ({} "
            "rows); largest per-cell change {:.4f} m at {:.2f} s = {:.2f} x "
            "the steady F = 0 99.9th percentile {:.4f} m\n",
            f.seamSeconds, o.playbackFps, c["frames_with_flat_rows"].get<std::size_t>(),
            c["flat_rows"].get<std::size_t>(), c["largest_change_m"].get<double>(),
            c["largest_change_at_s"].get<double>(), c["largest_over_steady_p999"].get<double>(),
            c["steady_f0_change_p999_m"].get<double>());
    }
    return 0;
}

} // namespace swell::play
