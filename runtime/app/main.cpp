// swell-play: headless replay of a .swell cache (paper Sec. 4): bench, height fields, shaded
// renders (Sec. 5) and fidelity against the simulated surface. Each subcommand is one file;
// this one wires them and turns every error into one line on stderr.

#include "command.h"
#include "play_common.h"

#include "swell/runtime/gl/egl_context.h"

#include <iostream>
#include <vector>

int main(int argc, char** argv) {
    using namespace swell::play;
    CLI::App app{"swell-play: headless replay of a .swell cache (stochastic slices, eq. 5-7)"};
    app.require_subcommand(1);
    std::vector<std::unique_ptr<Command>> commands;
    commands.push_back(makeBenchCommand());
    commands.push_back(makeHeightsCommand());
    commands.push_back(makeRenderCommand());
    commands.push_back(makeFidelityCommand());
    std::vector<CLI::App*> subcommands;
    for (const auto& c : commands)
        subcommands.push_back(c->add(app));
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "swell-play: " << e.what() << " (see --help)\n";
        return e.get_exit_code() != 0 ? e.get_exit_code() : 1;
    }
    try {
        swell::runtime::preferLlvmpipeThreads();
        int rc = 0;
        for (std::size_t i = 0; i < commands.size(); ++i) {
            if (*subcommands[i])
                rc = commands[i]->run();
        }
        for (const std::string& note : pendingNotes())
            std::cerr << "swell-play: note: " << note << "\n";
        return rc;
    } catch (const std::exception& e) { // cache, GL, parameter and I/O errors alike: one line
        std::cerr << "swell-play: " << e.what() << "\n";
    }
    return 1;
}
