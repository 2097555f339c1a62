#include "swell/cache/json_depth.h"

#include <algorithm>

namespace swell::cache {

std::size_t jsonNestingDepth(std::string_view text) {
    std::size_t depth = 0, deepest = 0;
    bool inString = false, escaped = false;
    for (const char c : text) {
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
            continue;
        }
        if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

std::string jsonDepthProblem(std::string_view text) {
    const std::size_t depth = jsonNestingDepth(text);
    if (depth <= kMaxJsonDepth)
        return std::string();
    return "nests " + std::to_string(depth) + " levels deep, more than the " +
           std::to_string(kMaxJsonDepth) + " allowed";
}

} // namespace swell::cache
