#pragma once
// A fresh folder for one test (suite): unique (mkdtemp under the system's temporary folder),
// removed with everything in it when the object goes.

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

namespace swell::test {

class TempDir {
public:
    /// Creates `<tmp>/<prefix>XXXXXX`. Throws std::runtime_error when it cannot.
    explicit TempDir(const std::string& prefix = "swell_test_") {
        std::string pattern =
            (std::filesystem::temp_directory_path() / (prefix + "XXXXXX")).string();
        if (::mkdtemp(pattern.data()) == nullptr)
            throw std::runtime_error("cannot create a temporary folder " + pattern);
        m_path = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return m_path; }
    std::filesystem::path operator/(const std::string& name) const { return m_path / name; }

private:
    std::filesystem::path m_path;
};

/// `name` in a temporary folder (one per prefix) that lives as long as the test program.
inline std::filesystem::path programTempFile(const std::string& prefix, const std::string& name) {
    static std::map<std::string, std::unique_ptr<TempDir>> byPrefix;
    auto& dir = byPrefix[prefix];
    if (!dir)
        dir = std::make_unique<TempDir>(prefix);
    return dir->path() / name;
}

} // namespace swell::test
