#pragma once
// Whether an output fits the free space of its file system, checked before a program writes
// it (swell-play heights and render, swell-cache synth). Header-only (target swell_cli).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace swell::cli {

/// Throws std::invalid_argument when `bytes` (the most `frames` frames written to `out` may
/// take) exceed the free space of the file system of `out`, or of its nearest existing parent
/// folder: "OPTION OUT: N frames may take up to X GB and FOLDER has Y GB free: about M frames
/// fit (ADVICE)". `option` is how the output was named on the command line ("--out", "OUT").
inline void checkDiskSpace(const std::string& option, const std::filesystem::path& out,
                           double bytes, std::size_t frames, const std::string& advice) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path folder = fs::absolute(out, ec);
    while (!folder.empty() && !fs::is_directory(folder, ec) && folder != folder.parent_path())
        folder = folder.parent_path();
    const fs::space_info space = fs::space(folder, ec);
    if (ec || bytes <= static_cast<double>(space.available))
        return;
    const double perFrame = bytes / static_cast<double>(std::max<std::size_t>(frames, 1));
    throw std::invalid_argument(fmt::format(
        "{} {}: {} frames may take up to {:.3g} GB (uncompressed) and {} has {:.3g} GB free: "
        "about {:.0f} frames fit ({})",
        option, out.string(), frames, bytes / 1e9, folder.string(),
        static_cast<double>(space.available) / 1e9,
        std::floor(static_cast<double>(space.available) / perFrame), advice));
}

} // namespace swell::cli
