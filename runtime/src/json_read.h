#pragma once
// Reading parameter structs from JSON with errors that name the key (replay and mode
// parameters): internal to the runtime library.

#include <fmt/format.h>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace swell::runtime::json_read {

/// Reads j[key] into `out` if present; names `prefix + key` in every error.
template <class T>
void read(const nlohmann::json& j, const char* key, const std::string& prefix, T& out) {
    if (!j.contains(key))
        return;
    try {
        out = j.at(key).get<T>();
    } catch (const nlohmann::json::exception& e) {
        throw std::invalid_argument(fmt::format("{}{}: {}", prefix, key, e.what()));
    }
}

/// Throws std::invalid_argument unless `j` is an object (naming `what`) whose keys are all in
/// `known` (naming `prefix + key`).
inline void rejectUnknown(const nlohmann::json& j, std::initializer_list<const char*> known,
                          const std::string& prefix, const std::string& what) {
    if (!j.is_object())
        throw std::invalid_argument(fmt::format("{}: expected a JSON object", what));
    for (const auto& item : j.items()) {
        bool ok = false;
        for (const char* k : known)
            ok = ok || item.key() == k;
        if (!ok)
            throw std::invalid_argument(fmt::format("unknown key {}{}", prefix, item.key()));
    }
}

} // namespace swell::runtime::json_read
