#pragma once
// One swell-play subcommand: it adds itself and its options to the command line, then runs.
// main.cpp only wires them (bench.cpp, heights.cpp, render.cpp, fidelity.cpp, look.cpp).

#include <CLI/CLI.hpp>
#include <memory>

namespace swell::play {

class Command {
public:
    virtual ~Command() = default;
    /// Adds the subcommand and its options to `app`; returns it.
    virtual CLI::App* add(CLI::App& app) = 0;
    /// Resolves and checks its options without reading the cache or touching the GPU; throws
    /// std::invalid_argument naming the option. run() needs it done first.
    virtual void check() = 0;
    /// Runs it (after check()); the exit status.
    virtual int run() = 0;
};

std::unique_ptr<Command> makeBenchCommand();
std::unique_ptr<Command> makeHeightsCommand();
std::unique_ptr<Command> makeRenderCommand();
std::unique_ptr<Command> makeFidelityCommand();
std::unique_ptr<Command> makeLookCommand();

} // namespace swell::play
