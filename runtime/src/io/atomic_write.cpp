#include "swell/runtime/io/atomic_write.h"

#include "swell/runtime/error.h"

#include <fmt/format.h>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace swell::runtime {

void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write) {
    std::filesystem::path temporary = path;
    temporary += ".tmp-" + std::to_string(::getpid());
    std::error_code ec;
    try {
        write(temporary);
    } catch (...) {
        std::filesystem::remove(temporary, ec);
        throw;
    }
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw RuntimeError(fmt::format("cannot write {}: {}", path.string(), ec.message()));
    }
}

void writeTextAtomically(const std::filesystem::path& path, const std::string& text) {
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out << text;
        out.close();
        if (!out)
            throw RuntimeError(fmt::format("cannot write {}", path.string()));
    });
}

} // namespace swell::runtime
