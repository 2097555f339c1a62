#include "swell/cache/checked_write.h"

#include <cerrno>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "swell/cache/output_lock.h"

namespace swell::cache {
namespace {

struct Fault {
    std::mutex mutex;
    bool loaded = false; // SWELL_FAULT_INJECT read
    bool armed = false;
    WriteFault spec;
    std::uint64_t left = 0; // bytes still allowed
};

Fault& state() {
    static Fault f;
    return f;
}

/// Bytes of a write of `size` that may go through; sets `error` when the fault triggers.
std::size_t allowed(std::size_t size, const std::filesystem::path& path, int& error) {
    Fault& f = state();
    std::lock_guard<std::mutex> lock(f.mutex);
    if (!f.loaded) {
        f.loaded = true;
        if (const char* spec = std::getenv("SWELL_FAULT_INJECT"); spec != nullptr && *spec) {
            f.spec = parseWriteFault(spec);
            f.left = f.spec.afterBytes;
            f.armed = true;
        }
    }
    error = 0;
    if (f.armed && !f.spec.match.empty() && path.string().find(f.spec.match) == std::string::npos)
        return size;
    if (!f.armed || size <= f.left) {
        if (f.armed)
            f.left -= size;
        return size;
    }
    const auto n = static_cast<std::size_t>(f.left);
    f.left = 0;
    error = f.spec.error;
    return n;
}

} // namespace

WriteFault parseWriteFault(const std::string& spec) {
    const auto bad = [&] {
        return std::invalid_argument("SWELL_FAULT_INJECT='" + spec +
                                     "': expected enospc:after=BYTES or eio:after=BYTES, "
                                     "optionally followed by :match=TEXT");
    };
    std::vector<std::string> parts;
    for (std::size_t start = 0;;) {
        const std::size_t colon = spec.find(':', start);
        parts.push_back(spec.substr(start, colon - start));
        if (colon == std::string::npos)
            break;
        start = colon + 1;
    }
    WriteFault f;
    if (parts.size() < 2 || parts.size() > 3)
        throw bad();
    if (parts[0] == "enospc")
        f.error = ENOSPC;
    else if (parts[0] == "eio")
        f.error = EIO;
    else
        throw bad();
    const std::string after = "after=", match = "match=";
    const std::string& n = parts[1];
    if (n.compare(0, after.size(), after) != 0 || n.size() == after.size() ||
        n.find_first_not_of("0123456789", after.size()) != std::string::npos ||
        n.size() - after.size() > 18)
        throw bad();
    f.afterBytes = std::stoull(n.substr(after.size()));
    if (parts.size() == 3) {
        if (parts[2].compare(0, match.size(), match) != 0 || parts[2].size() == match.size())
            throw bad();
        f.match = parts[2].substr(match.size());
    }
    return f;
}

void armWriteFault(const WriteFault& fault) {
    Fault& f = state();
    std::lock_guard<std::mutex> lock(f.mutex);
    f.loaded = true;
    f.armed = true;
    f.spec = fault;
    f.left = fault.afterBytes;
}

void disarmWriteFault() {
    Fault& f = state();
    std::lock_guard<std::mutex> lock(f.mutex);
    f.loaded = true;
    f.armed = false;
}

int writeAll(std::FILE* file, const void* data, std::size_t size,
             const std::filesystem::path& path) {
    int injected = 0;
    const std::size_t n = allowed(size, path, injected);
    if (n > 0 && std::fwrite(data, 1, n, file) != n)
        return errno != 0 ? errno : EIO;
    if (injected != 0) {
        std::fflush(file); // the bytes before the fault reach the file, as on a full disk
        return injected;
    }
    return 0;
}

int writeFile(const std::filesystem::path& path, const void* data, std::size_t size) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr)
        return errno != 0 ? errno : EIO;
    int err = writeAll(f, data, size, path);
    if (err == 0 && (std::fflush(f) != 0 || ::fsync(::fileno(f)) != 0))
        err = errno != 0 ? errno : EIO;
    if (std::fclose(f) != 0 && err == 0)
        err = errno != 0 ? errno : EIO;
    return err;
}

ReplaceResult replaceFile(const std::filesystem::path& path, const void* data, std::size_t size) {
    ReplaceResult r;
    r.temporary = temporaryPath(path);
    r.error = writeFile(r.temporary, data, size);
    r.step = "write";
    if (r.error == 0) {
        r.step = "rename";
        if (std::rename(r.temporary.c_str(), path.c_str()) != 0)
            r.error = errno != 0 ? errno : EIO;
    }
    if (r.error != 0) {
        std::error_code ignored;
        std::filesystem::remove(r.temporary, ignored);
        return r;
    }
    r.step = "";
    const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
    if (const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY); fd >= 0) {
        ::fsync(fd); // the rename itself survives a power cut
        ::close(fd);
    }
    return r;
}

} // namespace swell::cache
