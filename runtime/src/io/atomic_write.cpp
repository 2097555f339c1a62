#include "swell/runtime/io/atomic_write.h"

#include "swell/cache/checked_write.h"
#include "swell/cache/output_lock.h"
#include "swell/runtime/error.h"

#include <cstring>
#include <fmt/format.h>
#include <regex>
#include <set>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace swell::runtime {
namespace {
thread_local DeferredRenames* t_deferred = nullptr;
}

DeferredRenames::DeferredRenames() {
    if (t_deferred != nullptr)
        throw std::logic_error("DeferredRenames: one is already active on this thread");
    t_deferred = this;
}

DeferredRenames::~DeferredRenames() {
    if (t_deferred == this)
        t_deferred = nullptr;
    for (const auto& [temporary, path] : m_pending) {
        std::error_code ec;
        std::filesystem::remove(temporary, ec);
    }
}

NewFolders::~NewFolders() {
    for (auto it = m_made.rbegin(); it != m_made.rend(); ++it) {
        std::error_code ec;
        if (std::filesystem::is_empty(*it, ec) && !ec)
            std::filesystem::remove(*it, ec);
    }
}

void NewFolders::make(const std::filesystem::path& folder) {
    namespace fs = std::filesystem;
    std::vector<fs::path> missing;
    std::error_code ec;
    for (fs::path p = folder; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.parent_path())
            break;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        if (!fs::create_directory(*it, ec) && ec) {
            throw RuntimeError(
                fmt::format("cannot create the folder {}: {}", it->string(), ec.message()));
        }
        m_made.push_back(*it);
    }
}

void DeferredRenames::commit() {
    if (t_deferred == this)
        t_deferred = nullptr;
    m_active = false;
    while (!m_pending.empty()) {
        const auto [temporary, path] = m_pending.front();
        std::error_code ec;
        std::filesystem::rename(temporary, path, ec);
        if (ec)
            throw RuntimeError(fmt::format("cannot write {}: {}", path.string(), ec.message()));
        m_committed.push_back(path);
        m_pending.erase(m_pending.begin());
    }
}

void DeferredRenames::removeStaleSequenceFiles() const {
    static const std::regex kSequence(
        "(frame|height|normal|surface|splashes)_[0-9]{5}\\.(png|exr|ply)|disp_[0-9]{4}\\.exr");
    const std::set<std::filesystem::path> written(m_committed.begin(), m_committed.end());
    std::set<std::filesystem::path> folders;
    for (const auto& path : m_committed)
        folders.insert(path.parent_path());
    for (const auto& folder : folders) {
        std::error_code ec;
        std::vector<std::filesystem::path> stale;
        for (const auto& e : std::filesystem::directory_iterator(folder, ec)) {
            const std::string name = e.path().filename().string();
            if (e.is_regular_file() && std::regex_match(name, kSequence) &&
                !written.count(e.path()))
                stale.push_back(e.path());
        }
        for (const auto& path : stale) {
            std::filesystem::remove(path, ec);
            if (ec)
                throw RuntimeError(fmt::format("cannot remove {} (a frame of an earlier run): {}",
                                               path.string(), ec.message()));
        }
    }
}

void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write) {
    const std::filesystem::path temporary = cache::temporaryPath(path);
    std::error_code ec;
    try {
        write(temporary);
    } catch (...) {
        std::filesystem::remove(temporary, ec);
        throw;
    }
    if (t_deferred != nullptr) {
        for (const auto& pending : t_deferred->m_pending) {
            if (pending.first == temporary)
                return; // written again: the newer content is in the same temporary
        }
        t_deferred->m_pending.emplace_back(temporary, path);
        return;
    }
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw RuntimeError(fmt::format("cannot write {}: {}", path.string(), ec.message()));
    }
}

void writeBytesAtomically(const std::filesystem::path& path, std::string_view bytes) {
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        if (const int err = cache::writeFile(temporary, bytes.data(), bytes.size()); err != 0) {
            throw RuntimeError(fmt::format("cannot write {}: {}; no file was replaced",
                                           path.string(), std::strerror(err)));
        }
    });
}

void writeTextAtomically(const std::filesystem::path& path, const std::string& text) {
    writeBytesAtomically(path, text);
}

} // namespace swell::runtime
