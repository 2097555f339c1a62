// swell-play heights: the replay's height fields as 16-bit PNGs or OpenEXR, optionally normal
// maps and Blender's displacement sequence, with a JSON sidecar (format, scale, grid, frames,
// every parameter and the seed): height_sequence.h.

#include "command.h"
#include "play_common.h"

#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/io/atomic_write.h"
#include "swell/runtime/io/height_sequence.h"
#include "swell/runtime/modes/mode_replay.h"

#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <optional>

namespace swell::play {
namespace {

using namespace swell::runtime;

class HeightsCommand : public Command {
public:
    CLI::App* add(CLI::App& app) override {
        CLI::App* cmd =
            addSubcommand(app, "heights",
                          "write height fields (16-bit PNG or OpenEXR; normal maps, Blender "
                          "displacement) + JSON",
                          m_o);
        cmd->add_option("--out", m_outDir, "output folder")->required();
        cmd->add_option("--seconds", m_seconds, "simulated seconds to write")
            ->capture_default_str();
        addHeightFormatOption(cmd, m_format, "--format");
        cmd->add_flag("--normals", m_sequence.normals,
                      "also normal_NNNNN.exr: unit normals, R G B = x y z (world space, y up, "
                      "-1..1); half with exr-half, else float");
        cmd->add_flag("--blender-disp", m_sequence.displacement,
                      "also disp_NNNN.exr from disp_0001 (Blender frame 1), the layout of "
                      "Blender's Ocean bake: R G B = x y z displacement (m, y up), G = height - "
                      "the bake's still-water level (else y = 0); ZIP; half with exr-half, else "
                      "float");
        return cmd;
    }

    void check() override {
        finishOptions(m_o);
        checkSeconds(m_seconds, m_o.playbackFps);
        m_sequence.format = parseHeightFormat(m_format, "--format");
    }

    int run() override {
        const cache::Reader reader(m_o.cache);
        resolveFromCache(m_o, reader.header());
        const std::vector<double> taus = outputTaus(m_o, m_seconds);
        checkDiskSpace(m_outDir,
                       static_cast<double>(taus.size()) *
                           heightFrameBytes(m_sequence, m_o.params.cellsX, m_o.params.cellsZ),
                       taus.size());
        const TimelinePlan plan = planReplay(m_o, reader);
        // More output than the memory budget holds at once is replayed in chunks of output
        // frames, each with only its own frames decoded and uploaded: the same heights.
        const std::vector<SliceSampler> samplers = samplersOf(m_o, reader, plan);
        const std::vector<Chunk> chunks = streamChunks(m_o, reader, plan, samplers, taus);
        NewFolders folders; // removed again if the run fails
        folders.make(m_outDir);
        const EglContext context;
        std::optional<HeightSequence> sequence;
        json params;
        std::size_t decoded = 0;
        Progress progress("swell-play heights", taus.size(), !m_o.json);
        // The frames and the sidecar go under temporary names until all are complete
        // (atomic_write.h): a failed run leaves the folder as it was.
        DeferredRenames staged;
        for (const Chunk& chunk : chunks) {
            const std::vector<double> part(taus.begin() + static_cast<std::ptrdiff_t>(chunk.first),
                                           taus.begin() + static_cast<std::ptrdiff_t>(chunk.last));
            const ReplaySetup setup = replayOn(m_o, reader, plan, part, samplers);
            ModeReplay gpu(setup.set, m_o.params, m_o.modeParams, setup.samplers);
            if (!sequence) {
                sequence.emplace(m_outDir, m_sequence, heightScale(setup.set.header.domain),
                                 gpu.grid(), displacementReference(setup));
                params = paramsJson(m_o, setup);
            }
            decoded += setup.set.ids.size();
            for (std::size_t i = chunk.first; i < chunk.last; ++i) {
                gpu.update(taus[i]);
                sequence->write(i, gpu.readHeights(), taus[i], secondsOf(m_o, i));
                progress.step(i);
            }
        }
        progress.done();
        params["frames_decoded"] = decoded;
        params["memory"]["stream_chunks"] = chunks.size();
        const auto metaPath = sequence->writeSidecar(params, context.renderer());
        std::filesystem::remove(metaPath); // the old sidecar first: the folder is not whole
        staged.commit();                   // until the new one, renamed last
        staged.removeStaleSequenceFiles(); // no frames of an earlier, longer run
        folders.keep();
        if (m_o.json) {
            std::cout << json{{"out", m_outDir},
                              {"format", heightFormatName(m_sequence.format)},
                              {"count", taus.size()},
                              {"frames_decoded", decoded},
                              {"stream_chunks", chunks.size()},
                              {"memory", params["memory"]},
                              {"renderer", context.renderer()},
                              {"mode", m_o.mode},
                              {"seed", m_o.params.seed}}
                             .dump()
                      << "\n";
        } else {
            std::cout << fmt::format(
                "swell-play heights: {} frames ({}x{}, {}{}{}) in {}, metadata {} ({})\n",
                taus.size(), m_o.params.cellsX, m_o.params.cellsZ,
                heightFormatName(m_sequence.format), m_sequence.normals ? ", normals" : "",
                m_sequence.displacement ? ", Blender displacement" : "", m_outDir,
                metaPath.string(), context.renderer());
        }
        return 0;
    }

private:
    Options m_o;
    std::string m_outDir;
    double m_seconds = 2.0;
    std::string m_format = "png16";  ///< --format, parsed into m_sequence.format by run()
    HeightSequenceParams m_sequence; ///< what is written per frame
};

} // namespace

std::unique_ptr<Command> makeHeightsCommand() {
    return std::make_unique<HeightsCommand>();
}

} // namespace swell::play
