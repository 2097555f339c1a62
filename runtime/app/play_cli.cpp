#include "play_cli.h"

#include "command_line.h"
#include "option_words.h"

#include <stdexcept>

namespace swell::play {

PlayCommandLine::PlayCommandLine()
    : m_app("swell-play: headless replay of a .swell cache (stochastic slices, eq. 5-7)") {
    m_app.require_subcommand(1);
    m_commands.push_back(makeBenchCommand());
    m_commands.push_back(makeHeightsCommand());
    m_commands.push_back(makeRenderCommand());
    m_commands.push_back(makeFidelityCommand());
    m_commands.push_back(makeLookCommand());
    for (const auto& c : m_commands)
        m_subcommands.push_back(c->add(m_app));
}

std::optional<int> PlayCommandLine::parse(int argc, const char* const* argv, std::ostream& out,
                                          std::ostream& err) {
    if (const auto rc = cli::parse(m_app, argc, argv, "swell-play", out, err))
        return rc;
    for (std::size_t i = 0; i < m_subcommands.size(); ++i) {
        if (*m_subcommands[i])
            m_chosen = i;
    }
    try {
        command().check();
    } catch (const std::exception& e) { // an option value the subcommand refuses: one line
        err << "swell-play: " << cli::oneLine(inOptionWords(e.what())) << "\n";
        return cli::kExitBadInput;
    }
    return std::nullopt;
}

} // namespace swell::play
