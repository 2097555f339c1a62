#include "swell/runtime/replay/replay_memory.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace swell::runtime {
namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

/// "1.50 GiB", "12.3 MiB" or "640 KiB".
std::string size(std::size_t bytes) {
    const double b = static_cast<double>(bytes);
    if (b >= kGiB)
        return fmt::format("{:.2f} GiB", b / kGiB);
    if (b >= 1024.0 * 1024.0)
        return fmt::format("{:.1f} MiB", b / (1024.0 * 1024.0));
    return fmt::format("{:.0f} KiB", b / 1024.0);
}

} // namespace

ReplayMemory estimateReplayMemory(const cache::Reader& reader, std::span<const std::uint32_t> ids,
                                  const ReplayParams& params, std::size_t sliceSets,
                                  const Timeline& timeline) {
    ReplayMemory m;
    m.frames = ids.size();
    std::size_t surface = 0; // surface particles of the held frames
    for (std::uint32_t id : ids) {
        const cache::FrameInfo& info = reader.frameInfo(id);
        surface += info.surfaceCount;
        // Surface particles x, y; splash particles x, y, vx, vy (cache/frame.h).
        m.decodedBytes += (2 * static_cast<std::size_t>(info.surfaceCount) +
                           4 * static_cast<std::size_t>(info.splashCount)) *
                              sizeof(float) +
                          sizeof(cache::Frame);
    }
    const auto N = static_cast<std::size_t>(params.cellsX);
    const auto M = static_cast<std::size_t>(params.cellsZ);
    const std::size_t quads = (N + 3) / 4;
    const auto blendEntries =
        static_cast<std::size_t>(std::count_if(timeline.entries().begin(), timeline.entries().end(),
                                               [](const TimelineEntry& e) { return e.blended(); }));
    const std::size_t slots = ids.size() + blendEntries;
    const std::size_t columns = slots * quads * 8 * sizeof(float); // S and W per column quad
    const std::size_t particles = params.reconstruction == Reconstruction::Paper
                                      ? surface * 2 * sizeof(float) + slots * (N + 3) * 4
                                      : 0;
    const std::size_t tables = timeline.size() * 2 * sizeof(std::uint32_t); // slot, shown frame
    const std::size_t slices = static_cast<std::size_t>(2 * params.slices - 1) * 8;
    const std::size_t noise =
        static_cast<std::size_t>(params.noise.timeSamples) * params.slices * sizeof(double);
    const std::size_t heights = N * M * sizeof(float) * 2; // buffer + texture
    m.gpuBytes = sliceSets * (columns + particles + tables + slices + noise) + heights;
    m.stagingBytes = sliceSets * (columns + particles);
    return m;
}

std::size_t budgetBytes(double gibValue, const std::string& option) {
    if (!(gibValue > 0.0) || !std::isfinite(gibValue) || gibValue > 1024.0) {
        throw std::invalid_argument(
            fmt::format("{} must be in (0, 1024] GiB, got {}", option, gibValue));
    }
    return static_cast<std::size_t>(gibValue * kGiB);
}

void checkMemoryBudget(const ReplayMemory& m, std::size_t budget, const std::string& what,
                       const std::string& option, const std::string& advice) {
    if (m.total() <= budget)
        return;
    throw std::invalid_argument(fmt::format(
        "{} needs about {} ({} frames decoded: {}, GPU buffers: {}, upload copies: {}), above "
        "the memory budget of {} ({}): {}",
        what, size(m.total()), m.frames, size(m.decodedBytes), size(m.gpuBytes),
        size(m.stagingBytes), size(budget), option, advice));
}

} // namespace swell::runtime
