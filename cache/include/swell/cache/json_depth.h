#pragma once
// How deeply a JSON text nests its arrays and objects, read without parsing it. Every JSON text
// swell takes from a user or a file (scenes, --set values, cache metadata, C API parameters) is
// held to kMaxJsonDepth first: printing or comparing a value recurses once per level, so a
// value nested a million levels deep would overflow the stack instead of being refused.
#include <cstddef>
#include <string>
#include <string_view>

namespace swell::cache {

/// The deepest nesting swell accepts; its own scenes and metadata nest at most 6 levels.
inline constexpr std::size_t kMaxJsonDepth = 64;

/// The largest number of arrays and objects open at once in `text` (0 for a scalar), brackets
/// inside strings not counted. Defined for any text, valid JSON or not; linear, no allocation.
std::size_t jsonNestingDepth(std::string_view text);

/// Whether `text` nests at most kMaxJsonDepth levels.
inline bool jsonDepthAcceptable(std::string_view text) {
    return jsonNestingDepth(text) <= kMaxJsonDepth;
}

/// "" when `text` nests at most kMaxJsonDepth levels, else what every refusal says after naming
/// the text: "nests N levels deep, more than the 64 allowed".
std::string jsonDepthProblem(std::string_view text);

} // namespace swell::cache
