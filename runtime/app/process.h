#pragma once
// Running another program (ffmpeg for `render --video`) without a shell.

#include <string>
#include <vector>

namespace swell::play {

/// The executable `name` on PATH, or empty.
std::string findOnPath(const std::string& name);
/// Runs args[0] with arguments (no shell), waits; returns its exit status (-1: not run).
int runProcess(const std::vector<std::string>& args);

} // namespace swell::play
