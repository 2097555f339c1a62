// swell-play: headless replay of a .swell cache (paper Sec. 4): bench, height fields, shaded
// renders (Sec. 5) and fidelity against the simulated surface. Each subcommand is one file;
// play_cli.cpp parses and checks the command line, this one runs it and turns every error into
// one line on stderr.

#include "option_words.h"
#include "play_cli.h"
#include "play_common.h"

#include "exit_codes.h"

#include "swell/runtime/gl/egl_context.h"

#include <iostream>

int main(int argc, char** argv) {
    using namespace swell::play;
    PlayCommandLine cl;
    if (const auto rc = cl.parse(argc, argv, std::cout, std::cerr))
        return *rc;
    try {
        swell::runtime::preferLlvmpipeThreads();
        const int rc = cl.command().run();
        for (const std::string& note : pendingNotes())
            std::cerr << "swell-play: note: " << note << "\n";
        return rc;
    } catch (const std::exception& e) { // cache, GL, parameter and I/O errors alike: one line
        std::cerr << "swell-play: " << inOptionWords(e.what()) << "\n";
        return swell::cli::exitCodeFor(e);
    }
}
