// swell-play bench: frames per second of the GPU replay (every frame synced), per-stage GPU
// times, and the error against the double-precision CPU reference (docs/runtime.md).

#include "command.h"
#include "exit_codes.h"
#include "play_common.h"

#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/modes/mode_replay.h"

#include <algorithm>
#include <fmt/format.h>
#include <iostream>
#include <optional>

namespace swell::play {
namespace {

using namespace swell::runtime;

/// Wall time of every synced frame (the clock stops after glFinish), ms.
std::vector<double> syncedFrameMs(ModeReplay& gpu, std::span<const double> taus, int warmup) {
    for (int i = 0; i < warmup; ++i) {
        gpu.update(taus[static_cast<std::size_t>(i)]);
        gpu.finish();
    }
    std::vector<double> ms;
    for (std::size_t i = static_cast<std::size_t>(warmup); i < taus.size(); ++i) {
        const auto f0 = Clock::now();
        gpu.update(taus[i]);
        gpu.finish();
        ms.push_back(msSince(f0));
    }
    return ms;
}

/// Mean GPU time of each stage over `count` frames from `first` (timer queries: a run of their
/// own, since the queries cost a little).
StageTimes stageMeans(ModeReplay& gpu, std::span<const double> taus, int first, int count) {
    StageTimes sum;
    gpu.setTiming(true);
    for (int i = 0; i < count; ++i) {
        gpu.update(taus[static_cast<std::size_t>(first + i)]);
        sum += gpu.stageTimes();
    }
    gpu.setTiming(false);
    return sum.mean(count);
}

struct ReferenceCheck {
    HeightDifference difference; ///< GPU against the CPU reference
    bool framesExact = true;     ///< every slice chose the same frame as SliceSampler
    int frames = 0;
};

/// The GPU against the CPU reference on `count` frames evenly spread over the timed ones.
ReferenceCheck checkAgainstReference(ModeReplay& gpu, const CpuModeReference& cpu,
                                     const ReplaySetup& setup, std::span<const double> timed,
                                     int count) {
    ReferenceCheck c;
    c.frames = count;
    for (int e = 0; e < count; ++e) {
        const double tau =
            timed[static_cast<std::size_t>(e) * timed.size() / static_cast<std::size_t>(count)];
        gpu.update(tau);
        const auto sliceFrames = gpu.readSliceFrames();
        for (std::size_t d = 0; d < setup.samplers.size(); ++d)
            c.framesExact = c.framesExact && sliceFrames[d] == setup.samplers[d].frames(tau);
        c.difference.add(gpu.readHeights(), cpu.heights(tau));
    }
    return c;
}

class BenchCommand : public Command {
public:
    CLI::App* add(CLI::App& app) override {
        CLI::App* cmd = addSubcommand(
            app, "bench", "time the GPU replay and check it against the CPU reference", m_o);
        cmd->add_option("--frames", m_frames, "timed frames")
            ->capture_default_str()
            ->check(CLI::Range(1, 10000000));
        cmd->add_option("--warmup", m_warmup, "untimed frames first")
            ->capture_default_str()
            ->check(CLI::Range(0, 1000000));
        cmd->add_option("--error-frames", m_errorFrames, "frames compared with the CPU reference")
            ->capture_default_str()
            ->check(CLI::Range(0, 100000));
        cmd->add_option("--cpu-frames", m_cpuFrames, "frames timed on the CPU reference (0: skip)")
            ->capture_default_str()
            ->check(CLI::Range(0, 100000));
        cmd->add_option("--reference-cache", m_referenceCache,
                        "CPU reference reads its frames from this cache (same frame count), e.g. "
                        "the float32 original of a quantized cache; the error is then reported, "
                        "not judged");
        return cmd;
    }

    void check() override { finishOptions(m_o); }

    int run() override {
        const cache::Reader reader(m_o.cache);
        resolveFromCache(m_o, reader.header());
        const std::vector<double> taus =
            frameTaus(m_o, static_cast<std::size_t>(m_warmup + m_frames));
        auto t0 = Clock::now();
        const ReplaySetup setup = prepareReplay(m_o, reader, taus);
        const double decodeMs = msSince(t0);
        const EglContext context;
        const long long freeBefore = freeVideoMemoryKiB();
        t0 = Clock::now();
        ModeReplay gpu(setup.set, m_o.params, m_o.modeParams, setup.samplers);
        const double uploadMs = msSince(t0);
        gpu.finish();
        const long long freeAfter = freeVideoMemoryKiB();

        const std::vector<double> frameMs = syncedFrameMs(gpu, taus, m_warmup);
        const std::span<const double> timedTaus =
            std::span(taus).subspan(static_cast<std::size_t>(m_warmup));
        const int stageFrames = std::min(m_frames, 200);
        const StageTimes stage = stageMeans(gpu, taus, m_warmup, stageFrames);
        // With --reference-cache the reference reads the same frames from that cache (e.g. the
        // float32 original of a quantized cache), so the error includes the encoding's.
        std::optional<FrameSet> refSet;
        if (!m_referenceCache.empty())
            refSet = referenceFrames(reader, setup, taus);
        const CpuModeReference cpu(refSet ? *refSet : setup.set, m_o.params, m_o.modeParams,
                                   setup.samplers);
        const ReferenceCheck check =
            checkAgainstReference(gpu, cpu, setup, timedTaus, std::min(m_errorFrames, m_frames));
        const int cpuCount = std::min(m_cpuFrames, m_frames);
        t0 = Clock::now();
        for (int i = 0; i < cpuCount; ++i)
            (void)cpu.heights(timedTaus[static_cast<std::size_t>(i)]);
        const double cpuMs = cpuCount > 0 ? msSince(t0) / cpuCount : 0.0;

        json out = paramsJson(m_o, setup);
        out.update(
            report(context, gpu, setup, frameMs, stage, stageFrames, check, cpuCount, cpuMs));
        out.update({{"decode_ms", decodeMs}, {"upload_ms", uploadMs}});
        // Device memory the replay took, where the driver reports it (NVIDIA); null on Mesa.
        out["memory"]["gpu_used_kib_measured"] =
            freeBefore >= 0 && freeAfter >= 0 ? json(freeBefore - freeAfter) : json(nullptr);
        if (m_o.json)
            std::cout << out.dump() << "\n";
        else
            print(out, context, gpu, setup, frameMs, stage, check, cpuMs);
        return verdict(check, out["water_depth"].get<double>());
    }

private:
    /// The frames the replay holds, read from --reference-cache instead.
    FrameSet referenceFrames(const cache::Reader& reader, const ReplaySetup& setup,
                             const std::vector<double>& taus) const {
        const cache::Reader refReader(m_referenceCache);
        if (refReader.frameCount() != reader.frameCount()) {
            throw std::invalid_argument(fmt::format("--reference-cache {} has {} frames, {} has {}",
                                                    m_referenceCache, refReader.frameCount(),
                                                    m_o.cache, reader.frameCount()));
        }
        return loadUsed(refReader, setup.samplers, taus);
    }

    json report(const EglContext& context, const ModeReplay& gpu, const ReplaySetup& setup,
                const std::vector<double>& frameMs, const StageTimes& stage, int stageFrames,
                const ReferenceCheck& check, int cpuCount, double cpuMs) const {
        double total = 0.0;
        for (double ms : frameMs)
            total += ms;
        const double meanMs = total / static_cast<double>(frameMs.size());
        const double depth = waterDepth(setup.set);
        return {{"renderer", context.renderer()},
                {"llvmpipe_threads", context.llvmpipeThreads()},
                {"gl_version", context.version()},
                {"egl_platform", context.platform()},
                {"frames", m_frames},
                {"warmup", m_warmup},
                {"synced", true},
                {"fps", 1000.0 / meanMs},
                {"frame_ms_mean", meanMs},
                {"frame_ms_median", percentile(frameMs, 0.5)},
                {"frame_ms_p95", percentile(frameMs, 0.95)},
                {"stage_gpu_ms",
                 {{"slice_lookup", stage.sliceLookupMs},
                  {"reconstruct", stage.reconstructMs},
                  {"synthesis", stage.synthesisMs},
                  {"spiral_mapping", stage.spiralMs},
                  {"column_pass_once", gpu.columnPassMs()}}},
                {"slice_sets", setup.samplers.size()},
                {"timed_frames", stageFrames},
                {"timeline_search_ms", setup.plan.searchMs},
                {"uploaded_bytes", gpu.uploadedBytes()},
                {"error_frames", check.frames},
                {"frames_exact", check.framesExact},
                {"max_abs_error", check.difference.maxAbs},
                {"rms_error", check.difference.rms()},
                {"water_depth", depth},
                {"max_rel_error", check.difference.maxAbs / depth},
                {"reference_cache", m_referenceCache},
                {"cpu_reference_frames", cpuCount},
                {"cpu_reference_ms", cpuMs},
                {"cpu_reference_fps", cpuMs > 0.0 ? 1000.0 / cpuMs : 0.0}};
    }

    /// The text summary of report() `out`.
    void print(const json& out, const EglContext& context, const ModeReplay& gpu,
               const ReplaySetup& setup, const std::vector<double>& frameMs,
               const StageTimes& stage, const ReferenceCheck& check, double cpuMs) const {
        const double depth = out["water_depth"].get<double>();
        const ReplayParams& p = m_o.params;
        std::cout << fmt::format(
            "swell-play bench  {}  ({}, EGL {})\n"
            "  mode {}, {}x{} cells, K = {} ({} slices), seed {}, F {}, {} of {} cache frames "
            "decoded\n"
            "  {:.1f} fps synced over {} frames: median {:.3f} ms, p95 {:.3f} ms\n"
            "  GPU stages: slice lookup {:.4f} ms, reconstruct {:.4f} ms, synthesis {:.4f} ms, "
            "spiral mapping {:.4f} ms; column pass once {:.2f} ms\n"
            "  error vs CPU reference ({} frames): max {:.3g} m, rms {:.3g} m, max {:.3g} of depth "
            "{:.3g} m; frame choice {}\n"
            "  CPU reference: {:.1f} fps ({:.2f} ms/frame)\n",
            context.renderer(), context.version(), context.platform(), m_o.mode, p.cellsX, p.cellsZ,
            p.slices, 2 * p.slices - 1, p.seed, p.fluctuation, setup.set.ids.size(),
            setup.set.frameCount, out["fps"].get<double>(), m_frames, percentile(frameMs, 0.5),
            percentile(frameMs, 0.95), stage.sliceLookupMs, stage.reconstructMs, stage.synthesisMs,
            stage.spiralMs, gpu.columnPassMs(), check.frames, check.difference.maxAbs,
            check.difference.rms(), check.difference.maxAbs / depth, depth,
            check.framesExact ? "exact" : "DIFFERS", cpuMs > 0 ? 1000.0 / cpuMs : 0.0, cpuMs);
    }

    /// kExitOk, or kExitMissed when the GPU is not within 1e-4 of the depth of the reference or
    /// a frame choice differs (with --reference-cache the encodings differ: reported, not judged).
    int verdict(const ReferenceCheck& check, double depth) const {
        const double maxAbs = check.difference.maxAbs;
        if (!m_referenceCache.empty())
            return check.framesExact && std::isfinite(maxAbs) ? cli::kExitOk : cli::kExitMissed;
        if (!check.framesExact || !(maxAbs <= 1e-4 * depth)) {
            std::cerr << "swell-play: GPU result differs from the CPU reference beyond 1e-4 of the "
                         "depth\n";
            return cli::kExitMissed;
        }
        return cli::kExitOk;
    }

    Options m_o;
    int m_frames = 1000, m_warmup = 50, m_errorFrames = 8, m_cpuFrames = 3;
    std::string m_referenceCache;
};

} // namespace

std::unique_ptr<Command> makeBenchCommand() {
    return std::make_unique<BenchCommand>();
}

} // namespace swell::play
