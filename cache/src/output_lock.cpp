#include "swell/cache/output_lock.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace swell::cache {
namespace fs = std::filesystem;

fs::path lockPath(const fs::path& output) {
    fs::path p = output;
    p += ".lock";
    return p;
}

OutputLock::OutputLock(const fs::path& output) : m_path(lockPath(output)) {
    // The holder removes the lock file on release; a process that opened the old file just
    // before that locks an unlinked inode, so the lock counts only while the name still
    // refers to the locked file (checked after locking, retried otherwise).
    for (int attempt = 0; attempt < 100; ++attempt) {
        const int fd = ::open(m_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0)
            throw CacheError(output.string() + ": cannot create the lock file " + m_path.string() +
                             ": " + std::strerror(errno));
        struct flock lk {};
        lk.l_type = F_WRLCK;
        lk.l_whence = SEEK_SET;
        if (::fcntl(fd, F_SETLK, &lk) != 0) {
            const int err = errno;
            struct flock who {};
            who.l_type = F_WRLCK;
            who.l_whence = SEEK_SET;
            const bool known = ::fcntl(fd, F_GETLK, &who) == 0 && who.l_type != F_UNLCK;
            ::close(fd);
            if (err != EACCES && err != EAGAIN)
                throw CacheError(output.string() + ": cannot lock " + m_path.string() + ": " +
                                 std::strerror(err));
            if (!known)
                continue; // released in between: try again
            throw OutputBusy(output.string() + ": in use by process " + std::to_string(who.l_pid) +
                             " (lock " + m_path.string() +
                             "); wait for it to finish or write to another output");
        }
        struct stat a {
        }, b{};
        if (::fstat(fd, &a) == 0 && ::stat(m_path.c_str(), &b) == 0 && a.st_ino == b.st_ino &&
            a.st_dev == b.st_dev) {
            const std::string pid = std::to_string(::getpid()) + "\n";
            if (::ftruncate(fd, 0) == 0) // the PID, for people; the lock itself is what counts
                (void)!::write(fd, pid.data(), pid.size());
            m_fd = fd;
            return;
        }
        ::close(fd); // the file was removed by its previous holder: lock the new one
    }
    throw CacheError(output.string() + ": cannot lock " + m_path.string() +
                     ": it keeps being removed and recreated");
}

OutputLock::~OutputLock() {
    if (m_fd >= 0) {
        ::unlink(m_path.c_str()); // while still locked: the next holder checks the name
        ::close(m_fd);
    }
}

fs::path temporaryPath(const fs::path& path) {
    fs::path tmp = path;
    tmp += ".tmp-" + std::to_string(::getpid());
    return tmp;
}

long temporaryFileWriter(const fs::path& path) {
    const std::string f = path.filename().string();
    const std::size_t at = f.rfind(".tmp-");
    if (at == std::string::npos || at == 0)
        return 0;
    const std::string rest = f.substr(at + 5);
    if (rest.empty() || rest.size() > 9 ||
        rest.find_first_not_of("0123456789") != std::string::npos)
        return 0;
    return std::stol(rest);
}

bool processExists(long pid) {
    return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH);
}

} // namespace swell::cache
