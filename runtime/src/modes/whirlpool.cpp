#include "swell/runtime/modes/whirlpool.h"

#include "../smoothstep.h"

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
/// The filter's footprint, cells: the two cells that the surface's bilinear interpolation
/// between cell centres spans.
constexpr double kFootprintCells = 2.0;

/// x in [0, period): the floor-based remainder, with the rounding case x -> period folded to 0.
double wrap(double x, double period) {
    double w = x - period * std::floor(x / period);
    if (w >= period || w < 0.0)
        w = 0.0;
    return w;
}

/// The integral from v = 0 of a profile p linear between column centres (v = u - 1/2 the
/// column coordinate from the first centre), constant beyond the end centres, with
/// C[k] = integral to v = k (whirlpool.h).
double profileIntegral(const double* p, const double* C, int N, double v) {
    if (v <= 0.0)
        return v * p[0];
    if (v >= N - 1)
        return C[N - 1] + (v - (N - 1)) * p[N - 1];
    const int k = static_cast<int>(std::floor(v));
    const double a = v - k;
    return C[k] + a * p[k] + 0.5 * a * a * (p[k + 1] - p[k]);
}

/// C[k] for profileIntegral: the trapezoid sums of p to column centre k.
void integrate(const double* p, double* C, int N) {
    C[0] = 0.0;
    for (int k = 1; k < N; ++k)
        C[k] = C[k - 1] + 0.5 * (p[k - 1] + p[k]);
}

/// The integral of hat(x) = max(0, 1 - |x|) from -infinity to x.
double hatIntegral(double x) {
    if (x <= -1.0)
        return 0.0;
    if (x <= 0.0)
        return 0.5 * (x + 1.0) * (x + 1.0);
    if (x < 1.0)
        return 1.0 - 0.5 * (1.0 - x) * (1.0 - x);
    return 1.0;
}

} // namespace

double footprintWeight(double x, double w) {
    return (hatIntegral(0.5 * w - x) - hatIntegral(-0.5 * w - x)) / w;
}

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
    const double N = m_grid.cellsX;
    const double b = m_params.growth;
    const double cell = kFootprintCells * std::max(m_grid.dx, m_grid.dz);
    // Along the profile: |grad u| = N / (2 pi b r) columns per metre in the band; in the eye
    // the window widens from its width at r = a to the whole profile at the centre.
    const double atA = std::max(1.0, N / (kTwoPi * b * m_a) * cell);
    if (r <= m_a) {
        const double e = 1.0 - r / m_a;
        p.uWidth = std::max(atA, N * e);
    } else if (p.t < kTwoPi) {
        p.uWidth = std::max(1.0, N / (kTwoPi * b * r) * cell);
    }
    p.uWidth = std::min(p.uWidth, N);
    p.uCentre = std::clamp(p.u, 0.5 * p.uWidth, N - 0.5 * p.uWidth);
    // The spiral through P at parameter t starts at angle theta - t: slice coordinate.
    p.s = wrap((theta - p.t) * m_J / kTwoPi, static_cast<double>(m_J));
    // Across the spirals: |grad s| = J sqrt(1 + 1 / b^2) / (2 pi r) slices per metre.
    const double perMetre = m_J * std::sqrt(1.0 + 1.0 / (b * b)) / (kTwoPi * r);
    p.width = r > 0.0 ? std::clamp(perMetre * cell, 1.0, static_cast<double>(m_J))
                      : static_cast<double>(m_J);
    // Rankine funnel of depth D at the centre.
    const double D = m_params.eyeDepth;
    const double R = outerRadius();
    if (r <= m_a)
        p.dip = D * (1.0 - r * r / (2.0 * m_a * m_a));
    else if (r < R)
        p.dip = D * m_a * m_a / (2.0 * r * r) * (1.0 - smoothstep(m_a, R, r));
    return p;
}

double SpiralGeometry::spinSlices(double tau) const {
    return wrap(m_params.turnsPerTimeUnit * tau, 1.0) * m_J;
}

// ---------------------------------------------------------------------------------------------

CpuWhirlpool::CpuWhirlpool(const FrameSet& frames, const ReplayParams& params,
                           const WhirlpoolParams& whirlpool, const SliceSampler& sampler)
    : m_sampler(sampler), m_profiles(frames, params, sampler),
      m_geometry(m_profiles.grid(), whirlpool) {}

HeightField CpuWhirlpool::heights(double tau) const {
    const Grid& g = m_profiles.grid();
    const int N = g.cellsX;
    const int M = g.cellsZ;
    const int J = g.sliceCount();
    const Timeline& timeline = m_sampler.timeline();
    // Every spiral's profile p_j(n) at this tau (eq. 5 once per slice, blended in time) and
    // its integral along the profile.
    const std::size_t row = static_cast<std::size_t>(N);
    std::vector<double> p(static_cast<std::size_t>(J) * row);
    std::vector<double> C(p.size());
    for (int j = 0; j < J; ++j) {
        const SliceBlend b = m_sampler.blend(tau, j);
        double* pj = &p[static_cast<std::size_t>(j) * row];
        for (int n = 0; n < N; ++n) {
            pj[n] = m_profiles.profile(timeline[b.first], n);
            if (b.weight > 0.0)
                pj[n] =
                    (1.0 - b.weight) * pj[n] + b.weight * m_profiles.profile(timeline[b.second], n);
        }
        integrate(pj, &C[static_cast<std::size_t>(j) * row], N);
    }
    const double spin = m_geometry.spinSlices(tau);
    HeightField out;
    out.cellsX = N;
    out.cellsZ = M;
    out.heights.resize(static_cast<std::size_t>(N) * static_cast<std::size_t>(M));
    for (int m = 0; m < M; ++m) {
        for (int n = 0; n < N; ++n) {
            const SpiralPoint q = m_geometry.at(n, m);
            double s = q.s - spin; // the spirals turned by spin(tau)
            if (s < 0.0)
                s += J;
            // The box mean over the footprint: along the profile, the box of uWidth columns
            // around u; across, the spirals j with |j - s| < w / 2 + 1.
            const double v0 = q.uCentre - 0.5 - 0.5 * q.uWidth;
            const double v1 = q.uCentre - 0.5 + 0.5 * q.uWidth;
            const int first = static_cast<int>(std::floor(s - 0.5 * q.width)) - 1;
            const int last = static_cast<int>(std::floor(s + 0.5 * q.width)) + 1;
            double h = 0.0;
            for (int j = first; j <= last; ++j) {
                const double k = footprintWeight(j - s, q.width);
                if (k == 0.0)
                    continue;
                const std::size_t jw = static_cast<std::size_t>(((j % J) + J) % J) * row;
                h += k *
                     (profileIntegral(&p[jw], &C[jw], N, v1) -
                      profileIntegral(&p[jw], &C[jw], N, v0)) /
                     q.uWidth;
            }
            out.heights[static_cast<std::size_t>(m) * N + n] = h - q.dip;
        }
    }
    return out;
}

// ---------------------------------------------------------------------------------------------

GpuWhirlpool::GpuWhirlpool(const FrameSet& frames, const ReplayParams& params,
                           const WhirlpoolParams& whirlpool, const SliceSampler& sampler)
    : m_replay(frames, params, sampler), m_geometry(m_replay.grid(), whirlpool),
      m_out(m_replay.grid().cellsX, m_replay.grid().cellsZ) {
    const Grid& g = m_replay.grid();
    const int N = g.cellsX;
    const int M = g.cellsZ;
    struct GpuCell {
        float v, uWidth, s, width, dip, pad[3];
    };
    std::vector<GpuCell> cells(static_cast<std::size_t>(N) * static_cast<std::size_t>(M));
    for (int m = 0; m < M; ++m) {
        for (int n = 0; n < N; ++n) {
            const SpiralPoint p = m_geometry.at(n, m);
            float s = static_cast<float>(p.s);
            if (s >= static_cast<float>(g.sliceCount()))
                s = 0.0f; // float rounding at the wrap
            cells[static_cast<std::size_t>(m) * N + n] = {static_cast<float>(p.uCentre - 0.5),
                                                          static_cast<float>(p.uWidth),
                                                          s,
                                                          static_cast<float>(p.width),
                                                          static_cast<float>(p.dip),
                                                          {0.0f, 0.0f, 0.0f}};
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

    // Profiles from the column pass, once: its h = S / W, or the fallback when W = 0
    // (column_pass.comp's layout), stored per column centre k as (p(k), p(min(k + 1, N - 1)),
    // C(k) split into a float and the float of its remainder), C the profile's integral.
    const std::size_t slots = m_replay.slotCount();
    const int Nq = m_replay.columnQuads();
    std::vector<float> columns(std::max<std::size_t>(slots, 1) * static_cast<std::size_t>(Nq) * 8);
    glGetNamedBufferSubData(m_replay.columnBuffer(), 0,
                            static_cast<GLsizeiptr>(columns.size() * sizeof(float)),
                            columns.data());
    std::vector<float> pairs(std::max<std::size_t>(slots, 1) * static_cast<std::size_t>(N) * 4);
    auto profileAt = [&](std::size_t slot, int n) {
        const std::size_t base =
            ((slot * static_cast<std::size_t>(Nq) + static_cast<std::size_t>(n / 4)) * 2) * 4 +
            static_cast<std::size_t>(n % 4);
        return columns[base];
    };
    std::vector<double> prof(static_cast<std::size_t>(N)), C(static_cast<std::size_t>(N));
    for (std::size_t slot = 0; slot < slots; ++slot) {
        for (int n = 0; n < N; ++n)
            prof[static_cast<std::size_t>(n)] = profileAt(slot, n);
        integrate(prof.data(), C.data(), N);
        for (int n = 0; n < N; ++n) {
            float* q =
                &pairs[(slot * static_cast<std::size_t>(N) + static_cast<std::size_t>(n)) * 4];
            const double c = C[static_cast<std::size_t>(n)];
            q[0] = static_cast<float>(prof[static_cast<std::size_t>(n)]);
            q[1] = static_cast<float>(prof[static_cast<std::size_t>(std::min(n + 1, N - 1))]);
            q[2] = static_cast<float>(c);
            q[3] = static_cast<float>(c - static_cast<double>(q[2]));
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
    // spiral_prefix.comp's two tables: rows j = 0 .. J of N dvec2, (C, p) and (T, P).
    const std::size_t tableBytes = static_cast<std::size_t>(g.sliceCount() + 1) *
                                   static_cast<std::size_t>(N) * 2 * sizeof(double);
    if (static_cast<GLint64>(tableBytes) > maxBlock) {
        throw RuntimeError(fmt::format(
            "the whirlpool needs a {:.0f} MB table of the spirals' integrals, above this "
            "driver's {:.0f} MB shader-storage limit: lower --res or --slices",
            static_cast<double>(tableBytes) / 1e6, static_cast<double>(maxBlock) / 1e6));
    }
    m_along = makeStorageBuffer(tableBytes, nullptr);
    m_across = makeStorageBuffer(tableBytes, nullptr);
    m_uploadedBytes = m_replay.uploadedBytes() + cells.size() * sizeof(GpuCell) +
                      pairs.size() * sizeof(float) + 2 * tableBytes;
    m_prefix = makeEmbeddedProgram("spiral_prefix.comp");
    const GLuint pp = m_prefix.get();
    glProgramUniform1i(pp, uniformLocation(m_prefix, "u_N"), N);
    glProgramUniform1i(pp, uniformLocation(m_prefix, "u_J"), g.sliceCount());
    glProgramUniform1f(pp, uniformLocation(m_prefix, "u_missing"), m_replay.missingHeight());
    m_mapping = makeEmbeddedProgram("spiral_mapping.comp");
    const GLuint mp = m_mapping.get();
    glProgramUniform1i(mp, uniformLocation(m_mapping, "u_cells"), N * M);
    glProgramUniform1i(mp, uniformLocation(m_mapping, "u_N"), N);
    glProgramUniform1i(mp, uniformLocation(m_mapping, "u_J"), g.sliceCount());
    glProgramUniform1f(mp, uniformLocation(m_mapping, "u_reference"), m_replay.referenceHeight());
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
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m_replay.blendBuffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, m_along.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, m_across.get());
    glUseProgram(m_prefix.get());
    glDispatchCompute(static_cast<GLuint>((grid().cellsX + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
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
