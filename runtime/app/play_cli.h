#pragma once
// swell-play's command line: its subcommands (command.h), parsed and their options checked
// without reading a cache or touching the GPU, so that main.cpp and the options fuzz target
// (tests/fuzz/options_fuzz.cpp) share it.

#include "command.h"

#include <memory>
#include <optional>
#include <ostream>
#include <vector>

namespace swell::play {

class PlayCommandLine {
public:
    PlayCommandLine();
    /// Parses argv and checks the chosen subcommand's options (Command::check). Returns the exit
    /// status when swell-play should stop now: 0 after --help (printed on `out`); after a bad
    /// command line or an option value the subcommand refuses, one line "swell-play: ..."
    /// naming the option (option_words.h) on `err` and kExitBadInput; nullopt when it should go
    /// on and run command().
    std::optional<int> parse(int argc, const char* const* argv, std::ostream& out,
                             std::ostream& err);
    /// The chosen subcommand (after parse).
    Command& command() { return *m_commands[m_chosen]; }

private:
    CLI::App m_app;
    std::vector<std::unique_ptr<Command>> m_commands;
    std::vector<CLI::App*> m_subcommands;
    std::size_t m_chosen = 0;
};

} // namespace swell::play
