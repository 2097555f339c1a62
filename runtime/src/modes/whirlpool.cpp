#include "swell/runtime/modes/whirlpool.h"

#include "swell/runtime/error.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <stdexcept>

namespace swell::runtime {
namespace {

constexpr GLuint kGroup = 64; // local_size_x of spiral_mapping.comp
constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// x in [0, period): the floor-based remainder, with the rounding case x -> period folded to 0.
double wrap(double x, double period) {
    double w = x - period * std::floor(x / period);
    if (w >= period || w < 0.0)
        w = 0.0;
    return w;
}

/// Linear interpolation between column centres (whirlpool.h): lower column and weight.
void profileTap(double u, int N, int& n0, int& n1, double& beta) {
    const double fu = std::clamp(u - 0.5, 0.0, static_cast<double>(N - 1));
    n0 = std::max(0, std::min(static_cast<int>(std::floor(fu)), N - 2));
    n1 = std::min(n0 + 1, N - 1);
    beta = fu - n0;
}

/// The spirals show eq. (5)'s nearest frame: spiral_mapping.comp reads one column slot per
/// slice.
void requireNearest(const ReplayParams& params) {
    if (params.timeSampling != TimeSampling::Nearest) {
        throw std::invalid_argument(
            "--time-sampling linear is not available with --mode whirlpool (use nearest)");
    }
}

} // namespace

SpiralGeometry::SpiralGeometry(const Grid& grid, const WhirlpoolParams& params)
    : m_grid(grid), m_params(params), m_J(grid.sliceCount()),
      m_cx(grid.x0 + 0.5 * grid.cellsX * grid.dx), m_cz(0.5 * grid.extentZ),
      m_a(params.innerRadiusCells * grid.dx) {
    params.validate();
}

double SpiralGeometry::outerRadius() const {
    return m_a * std::exp(kTwoPi * m_params.growth);
}

SpiralPoint SpiralGeometry::at(int n, int m) const {
    const double px = m_grid.x0 + (n + 0.5) * m_grid.dx - m_cx;
    const double pz = (m + 0.5) * m_grid.dz - m_cz;
    const double r = std::hypot(px, pz);
    const double theta = std::atan2(pz, px);
    SpiralPoint p;
    // r = a e^(b t)  <=>  t = ln(r / a) / b; the eye (r < a) takes t = 0; beyond the outer
    // radius the spirals keep winding (t > 2 pi) but show their outer end (u = N).
    p.t = r > m_a ? std::log(r / m_a) / m_params.growth : 0.0;
    p.u = m_grid.cellsX * std::min(p.t, kTwoPi) / kTwoPi;
    // The spiral through P at parameter t starts at angle theta - t: slice coordinate.
    p.s = wrap((theta - p.t) * m_J / kTwoPi, static_cast<double>(m_J));
    return p;
}

double SpiralGeometry::spinSlices(double tau) const {
    return wrap(m_params.turnsPerTimeUnit * tau, 1.0) * m_J;
}

// ---------------------------------------------------------------------------------------------

CpuWhirlpool::CpuWhirlpool(const FrameSet& frames, const ReplayParams& params,
                           const WhirlpoolParams& whirlpool, const SliceSampler& sampler)
    : m_sampler(sampler), m_profiles(frames, params, sampler),
      m_geometry(m_profiles.grid(), whirlpool) {
    requireNearest(params);
}

HeightField CpuWhirlpool::heights(double tau) const {
    const Grid& g = m_profiles.grid();
    const int N = g.cellsX;
    const int M = g.cellsZ;
    const int J = g.sliceCount();
    const std::vector<std::size_t> entry = m_sampler.entries(tau); // eq. (5), once per slice
    const Timeline& timeline = m_sampler.timeline();
    const double spin = m_geometry.spinSlices(tau);
    HeightField out;
    out.cellsX = N;
    out.cellsZ = M;
    out.heights.resize(static_cast<std::size_t>(N) * static_cast<std::size_t>(M));
    for (int m = 0; m < M; ++m) {
        for (int n = 0; n < N; ++n) {
            const SpiralPoint p = m_geometry.at(n, m);
            double s = p.s - spin; // the spirals turned by spin(tau)
            if (s < 0.0)
                s += J;
            int j0 = static_cast<int>(std::floor(s));
            double alpha = s - j0;
            if (j0 >= J) {
                j0 = 0;
                alpha = 0.0;
            }
            const int j1 = j0 + 1 == J ? 0 : j0 + 1;
            int n0 = 0, n1 = 0;
            double beta = 0.0;
            profileTap(p.u, N, n0, n1, beta);
            auto along = [&](int j) { // the spiral's eq. (7) profile at u
                const TimelineEntry& f = timeline[entry[static_cast<std::size_t>(j)]];
                return (1.0 - beta) * m_profiles.profile(f, n0) + beta * m_profiles.profile(f, n1);
            };
            out.heights[static_cast<std::size_t>(m) * N + n] =
                (1.0 - alpha) * along(j0) + alpha * along(j1);
        }
    }
    return out;
}

// ---------------------------------------------------------------------------------------------

GpuWhirlpool::GpuWhirlpool(const FrameSet& frames, const ReplayParams& params,
                           const WhirlpoolParams& whirlpool, const SliceSampler& sampler)
    : m_replay(frames, params, sampler), m_geometry(m_replay.grid(), whirlpool),
      m_out(m_replay.grid().cellsX, m_replay.grid().cellsZ) {
    requireNearest(params);
    const Grid& g = m_replay.grid();
    const int N = g.cellsX;
    const int M = g.cellsZ;
    struct GpuCell {
        GLint n0;
        float beta, s, pad;
    };
    std::vector<GpuCell> cells(static_cast<std::size_t>(N) * static_cast<std::size_t>(M));
    for (int m = 0; m < M; ++m) {
        for (int n = 0; n < N; ++n) {
            const SpiralPoint p = m_geometry.at(n, m);
            int n0 = 0, n1 = 0;
            double beta = 0.0;
            profileTap(p.u, N, n0, n1, beta);
            float s = static_cast<float>(p.s);
            if (s >= static_cast<float>(g.sliceCount()))
                s = 0.0f; // float rounding at the wrap
            cells[static_cast<std::size_t>(m) * N + n] = {n0, static_cast<float>(beta), s, 0.0f};
        }
    }
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    if (static_cast<GLint64>(cells.size() * sizeof(GpuCell)) > maxBlock) {
        throw RuntimeError(
            fmt::format("the whirlpool needs a {:.0f} MB cell table, above this driver's {:.0f} MB "
                        "shader-storage limit: lower --res",
                        static_cast<double>(cells.size() * sizeof(GpuCell)) / 1e6,
                        static_cast<double>(maxBlock) / 1e6));
    }
    m_cells = makeStorageBuffer(cells.size() * sizeof(GpuCell), cells.data());

    // Profiles from the column pass, once: p = S / W, or the fallback S when W = 0
    // (column_pass.comp's layout), stored as pairs (p(n), p(min(n + 1, N - 1))).
    const std::size_t slots = m_replay.slotCount();
    const int Nq = m_replay.columnQuads();
    std::vector<float> columns(std::max<std::size_t>(slots, 1) * static_cast<std::size_t>(Nq) * 8);
    glGetNamedBufferSubData(m_replay.columnBuffer(), 0,
                            static_cast<GLsizeiptr>(columns.size() * sizeof(float)),
                            columns.data());
    std::vector<float> pairs(std::max<std::size_t>(slots, 1) * static_cast<std::size_t>(N) * 2);
    auto profileAt = [&](std::size_t slot, int n) {
        const std::size_t base =
            ((slot * static_cast<std::size_t>(Nq) + static_cast<std::size_t>(n / 4)) * 2) * 4 +
            static_cast<std::size_t>(n % 4);
        const float S = columns[base];
        const float W = columns[base + 4];
        return W > 0.0f ? S / W : S;
    };
    for (std::size_t slot = 0; slot < slots; ++slot) {
        for (int n = 0; n < N; ++n) {
            pairs[(slot * static_cast<std::size_t>(N) + static_cast<std::size_t>(n)) * 2] =
                profileAt(slot, n);
            pairs[(slot * static_cast<std::size_t>(N) + static_cast<std::size_t>(n)) * 2 + 1] =
                profileAt(slot, std::min(n + 1, N - 1));
        }
    }
    if (static_cast<GLint64>(pairs.size() * sizeof(float)) > maxBlock) {
        throw RuntimeError(fmt::format(
            "the whirlpool needs a {:.0f} MB profile table, above this driver's {:.0f} MB "
            "shader-storage limit: lower --res or replay fewer seconds",
            static_cast<double>(pairs.size() * sizeof(float)) / 1e6,
            static_cast<double>(maxBlock) / 1e6));
    }
    m_profiles = makeStorageBuffer(pairs.size() * sizeof(float), pairs.data());
    m_uploadedBytes =
        m_replay.uploadedBytes() + cells.size() * sizeof(GpuCell) + pairs.size() * sizeof(float);
    m_mapping = makeEmbeddedProgram("spiral_mapping.comp");
    const GLuint mp = m_mapping.get();
    glProgramUniform1i(mp, uniformLocation(m_mapping, "u_cells"), N * M);
    glProgramUniform1i(mp, uniformLocation(m_mapping, "u_N"), N);
    glProgramUniform1i(mp, uniformLocation(m_mapping, "u_J"), g.sliceCount());
    glProgramUniform1f(mp, uniformLocation(m_mapping, "u_reference"), m_replay.referenceHeight());
    glProgramUniform1f(mp, uniformLocation(m_mapping, "u_missing"), m_replay.missingHeight());
    m_spinLocation = uniformLocation(m_mapping, "u_spin");
    for (GlQuery& q : m_queries)
        q = makeTimestampQuery();
    checkGl("setting up the whirlpool");
}

void GpuWhirlpool::update(double tau) {
    m_timed = m_timing;
    if (m_timing)
        glQueryCounter(m_queries[0].get(), GL_TIMESTAMP);
    m_replay.lookupSlices(tau); // eq. (5)-(6) (validates tau); its memory barrier follows
    if (m_timing)
        glQueryCounter(m_queries[1].get(), GL_TIMESTAMP);
    float spin = static_cast<float>(m_geometry.spinSlices(tau)); // wrapped in double first
    if (spin >= static_cast<float>(m_geometry.sliceCount()))
        spin = 0.0f;
    glProgramUniform1f(m_mapping.get(), m_spinLocation, spin);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m_replay.sliceBuffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m_profiles.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m_cells.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m_out.buffer());
    glUseProgram(m_mapping.get());
    const long long cells = static_cast<long long>(grid().cellsX) * grid().cellsZ;
    glDispatchCompute(static_cast<GLuint>((cells + kGroup - 1) / kGroup), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_PIXEL_BUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    if (m_timing)
        glQueryCounter(m_queries[2].get(), GL_TIMESTAMP);
    m_out.markWritten();
}

StageTimes GpuWhirlpool::stageTimes() const {
    if (!m_timed)
        throw std::logic_error("GpuWhirlpool::stageTimes: no timed update yet");
    StageTimes t;
    t.sliceLookupMs = elapsedMs(m_queries[0], m_queries[1]);
    t.spiralMs = elapsedMs(m_queries[1], m_queries[2]);
    return t;
}

} // namespace swell::runtime
