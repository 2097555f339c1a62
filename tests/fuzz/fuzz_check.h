#pragma once
// What every fuzz target (tests/fuzz) asks of an input it refuses: one clear error line. A
// breach prints the input's problem and aborts, which libFuzzer and the corpus replay
// (fuzz_replay_main.cpp) both report as a failure.

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace swell::fuzz {

[[noreturn]] inline void fail(std::string_view what, std::string_view detail) {
    std::fprintf(stderr, "swell fuzz: %.*s: %.*s\n", static_cast<int>(what.size()), what.data(),
                 static_cast<int>(detail.size()), detail.data());
    std::abort();
}

/// A refusal's message must be one non-empty line that starts with `prefix`.
inline void requireClearError(std::string_view message, std::string_view prefix) {
    if (message.empty())
        fail("empty error message", message);
    if (message.find('\n') != std::string_view::npos ||
        message.find('\r') != std::string_view::npos)
        fail("error message spans several lines", message);
    if (message.substr(0, prefix.size()) != prefix)
        fail("error message does not start with the expected prefix", message);
}

inline void require(bool ok, std::string_view what, std::string_view detail = {}) {
    if (!ok)
        fail(what, detail);
}

} // namespace swell::fuzz
