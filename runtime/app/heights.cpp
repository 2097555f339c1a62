// swell-play heights: the replay's height fields as 16-bit PNGs with a JSON sidecar (scale,
// grid, every parameter and the seed).

#include "command.h"
#include "play_common.h"

#include "swell/runtime/gl/egl_context.h"
#include "swell/runtime/io/height_png.h"
#include "swell/runtime/modes/mode_replay.h"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iostream>

namespace swell::play {
namespace {

using namespace swell::runtime;

class HeightsCommand : public Command {
public:
    CLI::App* add(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("heights", "write height fields (16-bit PNG + JSON)");
        addCommon(cmd, m_o);
        cmd->add_option("--out", m_outDir, "output folder")->required();
        cmd->add_option("--seconds", m_seconds, "simulated seconds to write")
            ->capture_default_str();
        return cmd;
    }

    int run() override {
        finishOptions(m_o);
        checkSeconds(m_seconds);
        const cache::Reader reader(m_o.cache);
        resolveAutoRes(m_o, reader.header());
        const std::vector<double> taus = outputTaus(m_o, m_seconds);
        const ReplaySetup setup = prepareReplay(m_o, reader, taus);
        std::filesystem::create_directories(m_outDir);
        const EglContext context;
        ModeReplay gpu(setup.set, m_o.params, m_o.modeParams, setup.samplers);
        const HeightScale scale = heightScale(setup.set.header.domain);
        json frames = json::array();
        Progress progress("swell-play heights", taus.size(), !m_o.json);
        for (std::size_t i = 0; i < taus.size(); ++i) {
            gpu.update(taus[i]);
            const std::string name = fmt::format("height_{:05d}.png", i);
            writeHeightPng(std::filesystem::path(m_outDir) / name, gpu.readHeights(), scale);
            frames.push_back({{"file", name}, {"tau", taus[i]}, {"seconds", secondsOf(m_o, i)}});
            progress.step(i);
        }
        progress.done();
        const auto metaPath = std::filesystem::path(m_outDir) / "heights.json";
        std::ofstream(metaPath) << heightsSidecar(paramsJson(m_o, setup), scale, gpu.grid(),
                                                  context.renderer(), frames)
                                       .dump(2)
                                << "\n";
        if (m_o.json) {
            std::cout << json{{"out", m_outDir},
                              {"count", taus.size()},
                              {"frames_decoded", setup.set.ids.size()},
                              {"renderer", context.renderer()},
                              {"mode", m_o.mode},
                              {"seed", m_o.params.seed}}
                             .dump()
                      << "\n";
        } else {
            std::cout << fmt::format(
                "swell-play heights: {} frames ({}x{}) in {}, metadata {} ({})\n", taus.size(),
                m_o.params.cellsX, m_o.params.cellsZ, m_outDir, metaPath.string(),
                context.renderer());
        }
        return 0;
    }

private:
    Options m_o;
    std::string m_outDir;
    double m_seconds = 2.0;
};

} // namespace

std::unique_ptr<Command> makeHeightsCommand() {
    return std::make_unique<HeightsCommand>();
}

} // namespace swell::play
