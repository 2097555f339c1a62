#pragma once
// GLSL sources from shaders/, embedded at build time (shaders/CMakeLists.txt).

#include <span>
#include <string_view>

namespace swell::shaders {

/// One embedded shader: its file name (e.g. "reconstruct.comp") and full text.
struct Source {
    std::string_view name;
    std::string_view text;
};

/// Every embedded shader, in the order of shaders/CMakeLists.txt.
std::span<const Source> all();
/// The text of shader `name`; a missing name is a bug (throws std::logic_error).
std::string_view get(std::string_view name);

} // namespace swell::shaders
