#include "swell/runtime/replay/cpu_reconstruction.h"

#include "swell/runtime/replay/surface_envelope.h"

#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <stdexcept>

namespace swell::runtime {

ColumnSum blendColumns(ColumnSum a, ColumnSum b, double alpha) {
    const double h = (1.0 - alpha) * a.height() + alpha * b.height();
    const double W = (1.0 - alpha) * a.W + alpha * b.W;
    return W > 0.0 ? ColumnSum{h * W, W} : ColumnSum{h, 0.0};
}

std::vector<int> windowSlices(const Grid& grid, int m) {
    // z_j - P_z in [-dz, dz)  <=>  -2K <= (j + 1) M - (2m + 1) K < 2K  (exact in integers)
    const long long M = grid.cellsZ;
    const long long K = grid.slices;
    std::vector<int> row;
    int best = 0;
    long long bestDistance = -1;
    for (int j = 0; j < grid.sliceCount(); ++j) {
        const long long d = (j + 1) * M - (2LL * m + 1) * K;
        if (d >= -2 * K && d < 2 * K)
            row.push_back(j);
        if (bestDistance < 0 || std::llabs(d) < bestDistance) {
            best = j;
            bestDistance = std::llabs(d);
        }
    }
    if (row.empty())
        row.push_back(best);
    return row;
}

CpuReconstruction::CpuReconstruction(const FrameSet& frames, const ReplayParams& params,
                                     const SliceSampler& sampler)
    : m_frames(frames), m_sampler(sampler), m_params(params),
      m_grid(makeGrid(frames.header, params)) {
    params.validate();
    frames.validate();
    const int N = m_grid.cellsX;
    const int M = m_grid.cellsZ;

    // Per frame: particles grouped by x bin b = floor((x - xMin) / dx), bins -1 .. N.
    m_binned.resize(frames.frames.size());
    for (std::size_t i = 0; i < frames.frames.size(); ++i) {
        const std::vector<float>& s = frames.frames[i].surface;
        std::vector<std::vector<std::pair<double, double>>> bins(static_cast<std::size_t>(N + 2));
        for (std::size_t p = 0; p + 1 < s.size(); p += 2) {
            const double u = (static_cast<double>(s[p]) - m_grid.x0) / m_grid.dx;
            const double b = std::floor(u);
            if (b < -1.0 || b > N)
                continue; // beyond every window
            bins[static_cast<std::size_t>(b + 1.0)].emplace_back(u, static_cast<double>(s[p + 1]));
        }
        BinnedFrame& f = m_binned[i];
        f.start.push_back(0);
        for (const auto& bin : bins) {
            for (const auto& [u, h] : bin) {
                f.u.push_back(u);
                f.h.push_back(h);
            }
            f.start.push_back(static_cast<std::uint32_t>(f.u.size()));
        }
    }

    if (params.reconstruction == Reconstruction::Envelope) {
        const double binWidth = envelopeBinWidth(frames.header, m_grid);
        m_envelope.resize(frames.frames.size());
        for (std::size_t i = 0; i < frames.frames.size(); ++i) // empty: no surface particle
            m_envelope[i] = sampleEnvelope(SurfaceEnvelope(frames.frames[i], binWidth), m_grid.x0,
                                           m_grid.dx, N);
    }

    m_rowSlices.resize(static_cast<std::size_t>(M));
    for (int m = 0; m < M; ++m)
        m_rowSlices[static_cast<std::size_t>(m)] = windowSlices(m_grid, m);
}

const CpuReconstruction::BinnedFrame& CpuReconstruction::binned(std::uint32_t frame) const {
    const cache::Frame* f = m_frames.find(frame);
    if (f == nullptr) {
        throw std::invalid_argument(
            fmt::format("frame {} is selected by a slice but not in the frame set", frame));
    }
    return m_binned[static_cast<std::size_t>(f - m_frames.frames.data())];
}

double CpuReconstruction::fallback(const BinnedFrame& f, int n) const {
    const int N = m_grid.cellsX;
    auto binRange = [&](int b) {
        return std::pair{f.start[static_cast<std::size_t>(b + 1)],
                         f.start[static_cast<std::size_t>(b + 2)]};
    };
    for (int d = 2; n - d >= -1 || n + d <= N; ++d) {
        double sum = 0.0;
        std::uint32_t count = 0;
        for (int b : {n - d, n + d}) {
            if (b < -1 || b > N)
                continue;
            const auto [first, last] = binRange(b);
            for (std::uint32_t p = first; p < last; ++p)
                sum += f.h[p];
            count += last - first;
        }
        if (count > 0)
            return sum / count;
    }
    return m_frames.header.domain.yMin; // the frame has no surface particle
}

ColumnSum CpuReconstruction::column(std::uint32_t frame, int n) const {
    if (n < 0 || n >= m_grid.cellsX)
        throw std::logic_error(fmt::format("profile column {} outside 0 .. {}", n, m_grid.cellsX));
    const BinnedFrame& f = binned(frame);
    if (m_params.reconstruction == Reconstruction::Envelope) {
        const auto& eta = m_envelope[static_cast<std::size_t>(&f - m_binned.data())];
        return eta.empty() ? ColumnSum{m_frames.header.domain.yMin, 0.0}
                           : ColumnSum{eta[static_cast<std::size_t>(n)], 1.0};
    }
    const double inv2s2 = 1.0 / (2.0 * m_params.sigma * m_params.sigma);
    const double Px = n + 0.5;
    double sumGh = 0.0;
    double sumG = 0.0;
    for (std::uint32_t p = f.start[static_cast<std::size_t>(n)];
         p < f.start[static_cast<std::size_t>(n + 3)]; ++p) {
        const double dx = f.u[p] - Px;
        const double G = std::exp(-dx * dx * inv2s2); // eq. (7), x factor (G_z cancels)
        sumGh += G * f.h[p];
        sumG += G;
    }
    return sumG > 0.0 ? ColumnSum{sumGh, sumG} : ColumnSum{fallback(f, n), 0.0};
}

ColumnSum CpuReconstruction::column(const TimelineEntry& e, int n) const {
    if (!e.blended())
        return column(e.a, n);
    return blendColumns(column(e.a, n), column(e.b, n), e.alpha);
}

HeightField CpuReconstruction::heights(double tau) const {
    const int N = m_grid.cellsX;
    const int M = m_grid.cellsZ;
    const Timeline& timeline = m_sampler.timeline();
    // eq. (5), once per slice: the entries around its frame number and the fraction between.
    std::vector<SliceBlend> slice(static_cast<std::size_t>(m_sampler.sliceCount()));
    for (std::size_t j = 0; j < slice.size(); ++j)
        slice[j] = m_sampler.blend(tau, static_cast<int>(j));
    // Slices read straight from their particles (the paper's eq. (7) on one frame); the others
    // (cross-fades, time blends, envelope profiles) through their column sums.
    const bool direct = m_params.reconstruction == Reconstruction::Paper;
    std::vector<const BinnedFrame*> frameOf(slice.size(), nullptr);
    for (std::size_t j = 0; j < slice.size(); ++j) {
        for (const std::size_t i : {slice[j].first, slice[j].second}) {
            const TimelineEntry& e = timeline[i];
            const BinnedFrame& a = binned(e.a); // throws when a frame is not held
            if (e.blended())
                (void)binned(e.b);
            else if (direct && slice[j].weight == 0.0)
                frameOf[j] = &a;
        }
    }
    auto sliceColumn = [&](std::size_t j, int n) {
        const SliceBlend& b = slice[j];
        const ColumnSum c = column(timeline[b.first], n);
        return b.weight == 0.0 ? c : blendColumns(c, column(timeline[b.second], n), b.weight);
    };

    const double inv2s2 = 1.0 / (2.0 * m_params.sigma * m_params.sigma);
    HeightField out;
    out.cellsX = N;
    out.cellsZ = M;
    out.heights.resize(static_cast<std::size_t>(N) * static_cast<std::size_t>(M));
    for (int m = 0; m < M; ++m) {
        const double Pz = m + 0.5;
        for (int n = 0; n < N; ++n) {
            const double Px = n + 0.5;
            double sumGh = 0.0;
            double sumG = 0.0;
            // One slice in the row (always so when M > 2K: the nearest one): its G_z cancels
            // and is taken as 1, since far from the slice it underflows to 0 (0 / 0 = NaN).
            const bool single = m_rowSlices[static_cast<std::size_t>(m)].size() == 1;
            for (int j : m_rowSlices[static_cast<std::size_t>(m)]) {
                const double dz = single ? 0.0 : m_grid.sliceZCells(j) - Pz;
                if (frameOf[static_cast<std::size_t>(j)] == nullptr) {
                    const ColumnSum c = sliceColumn(static_cast<std::size_t>(j), n);
                    const double Gz = std::exp(-dz * dz * inv2s2);
                    if (c.W > 0.0) {
                        sumGh += Gz * c.S;
                        sumG += Gz * c.W;
                    }
                    continue;
                }
                const BinnedFrame& f = *frameOf[static_cast<std::size_t>(j)];
                const std::uint32_t first = f.start[static_cast<std::size_t>(n)]; // bin n - 1
                const std::uint32_t last =
                    f.start[static_cast<std::size_t>(n + 3)]; // bin n + 1 end
                for (std::uint32_t p = first; p < last; ++p) {
                    const double dx = f.u[p] - Px;
                    const double G = std::exp(-(dx * dx + dz * dz) * inv2s2); // eq. (7) weight
                    sumGh += G * f.h[p];
                    sumG += G;
                }
            }
            double h = 0.0;
            if (sumG > 0.0) {
                h = sumGh / sumG; // eq. (7)
            } else {
                double sumF = 0.0;
                double sumGz = 0.0;
                for (int j : m_rowSlices[static_cast<std::size_t>(m)]) {
                    const double dz = single ? 0.0 : m_grid.sliceZCells(j) - Pz;
                    const double Gz = std::exp(-dz * dz * inv2s2);
                    const BinnedFrame* f = frameOf[static_cast<std::size_t>(j)];
                    sumF += Gz * (f != nullptr ? fallback(*f, n)
                                               : sliceColumn(static_cast<std::size_t>(j), n).S);
                    sumGz += Gz;
                }
                h = sumF / sumGz;
            }
            out.heights[static_cast<std::size_t>(m) * N + n] = h;
        }
    }
    return out;
}

} // namespace swell::runtime
