#include "swell/runtime/modes/ripple.h"

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

constexpr GLuint kGroup = 64; // local_size_x of ripple_synthesis.comp

/// Bilinear neighbours along x at cell coordinate `c`, clamped to the edge columns
/// (definitions in ripple.h): lower index, upper index, fraction.
void clampedTap(double c, int cells, int& i0, int& i1, double& f) {
    const double fc = std::clamp(c - 0.5, 0.0, static_cast<double>(cells - 1));
    i0 = std::max(0, std::min(static_cast<int>(std::floor(fc)), cells - 2));
    i1 = std::min(i0 + 1, cells - 1);
    f = fc - i0;
}

/// Bilinear neighbours along z at cell coordinate `c`, periodic with period `cells`.
void periodicTap(double c, int cells, int& i0, int& i1, double& f) {
    const double period = static_cast<double>(cells);
    double fc = (c - 0.5) - period * std::floor((c - 0.5) / period);
    if (fc >= period || fc < 0.0)
        fc = 0.0; // rounding at the wrap
    i0 = std::min(static_cast<int>(std::floor(fc)), cells - 1);
    i1 = i0 + 1 == cells ? 0 : i0 + 1;
    f = fc - i0;
}

void checkSamplers(const ModeParams& mode, std::span<const SliceSampler> samplers) {
    if (samplers.size() != static_cast<std::size_t>(mode.sliceSets()))
        throw std::logic_error("ripple: one slice sampler per direction is needed");
}

} // namespace

double rippleEdgeWeight(double u, int N, double side) {
    const double margin = kRippleEdgeMargin * N;
    const double a = std::min(u, N - u) + std::max(margin - side, 0.0);
    return kRippleEdgeFloor + (1.0 - kRippleEdgeFloor) * smoothstep(0.0, margin, a);
}

bool rippleIsIdentity(const RippleParams& ripple) {
    return ripple.anglesDegrees.size() == 1 && ripple.anglesDegrees[0] == 0.0;
}

std::vector<RippleTap> rippleTaps(const Grid& grid, const RippleParams& ripple) {
    ripple.validate();
    const int N = grid.cellsX;
    const int M = grid.cellsZ;
    const std::size_t D = ripple.anglesDegrees.size();
    const std::vector<double> omega = ripple.normalisedWeights();
    const double Cx = grid.x0 + 0.5 * N * grid.dx;
    const double Cz = 0.5 * grid.extentZ;
    std::vector<double> cosA(D), sinA(D);
    for (std::size_t d = 0; d < D; ++d) {
        const double a = ripple.anglesDegrees[d] * std::numbers::pi / 180.0;
        cosA[d] = std::cos(a);
        sinA[d] = std::sin(a);
    }
    std::vector<RippleTap> taps(static_cast<std::size_t>(N) * static_cast<std::size_t>(M) * D);
    for (int m = 0; m < M; ++m) {
        for (int n = 0; n < N; ++n) {
            const double px = grid.x0 + (n + 0.5) * grid.dx - Cx;
            const double pz = (m + 0.5) * grid.dz - Cz;
            // Distance to the base mesh's nearest side, in cells of dx.
            const double side = std::min(0.5 * N - std::abs(px) / grid.dx,
                                         (0.5 * grid.extentZ - std::abs(pz)) / grid.dx);
            RippleTap* cell =
                &taps[(static_cast<std::size_t>(m) * static_cast<std::size_t>(N) + n) * D];
            for (std::size_t d = 0; d < D; ++d) {
                // q = R(-a_d) (P - C) + C, in direction d's cell coordinates
                const double qx = cosA[d] * px + sinA[d] * pz;
                const double qz = -sinA[d] * px + cosA[d] * pz;
                const double u = (qx + Cx - grid.x0) / grid.dx;
                const double v = (qz + Cz) / grid.dz;
                RippleTap& t = cell[d];
                t.inside = u >= 0.0 && u <= N && v >= 0.0 && v <= M;
                clampedTap(u, N, t.n0, t.n1, t.fx);
                periodicTap(v, M, t.m0, t.m1, t.fz);
                t.weight = omega[d] * rippleEdgeWeight(u, N, side); // eq. (8)'s omega_d, tapered
            }
            double sum = 0.0;
            for (std::size_t d = 0; d < D; ++d)
                sum += cell[d].weight;
            for (std::size_t d = 0; d < D; ++d)
                cell[d].weight /= sum;
        }
    }
    return taps;
}

// ---------------------------------------------------------------------------------------------

CpuRipple::CpuRipple(const FrameSet& frames, const ReplayParams& params, const RippleParams& ripple,
                     std::span<const SliceSampler> samplers)
    : m_grid(makeGrid(frames.header, params)), m_D(static_cast<int>(ripple.anglesDegrees.size())) {
    ModeParams mode;
    mode.mode = ReplayMode::Ripple;
    mode.ripple = ripple;
    mode.validate();
    checkSamplers(mode, samplers);
    for (int d = 0; d < m_D; ++d) {
        m_dirs.push_back(std::make_unique<CpuReconstruction>(
            frames, sliceSetParams(params, d), samplers[static_cast<std::size_t>(d)]));
    }
    m_taps = rippleTaps(m_grid, ripple);
}

HeightField CpuRipple::heights(double tau) const {
    std::vector<HeightField> dir;
    for (const auto& r : m_dirs)
        dir.push_back(r->heights(tau)); // Algorithm 2b, steps 3-8: eq. (5)-(7) per direction
    const int N = m_grid.cellsX;
    const int M = m_grid.cellsZ;
    HeightField out;
    out.cellsX = N;
    out.cellsZ = M;
    out.heights.assign(static_cast<std::size_t>(N) * static_cast<std::size_t>(M), 0.0);
    for (std::size_t c = 0; c < out.heights.size(); ++c) {
        double h = 0.0;
        for (int d = 0; d < m_D; ++d) {
            const RippleTap& t = m_taps[c * static_cast<std::size_t>(m_D) + d];
            const HeightField& f = dir[static_cast<std::size_t>(d)];
            const double lo = (1.0 - t.fx) * f.at(t.n0, t.m0) + t.fx * f.at(t.n1, t.m0);
            const double hi = (1.0 - t.fx) * f.at(t.n0, t.m1) + t.fx * f.at(t.n1, t.m1);
            h += t.weight * ((1.0 - t.fz) * lo + t.fz * hi); // eq. (8)
        }
        out.heights[c] = h;
    }
    return out;
}

// ---------------------------------------------------------------------------------------------

GpuRipple::GpuRipple(const FrameSet& frames, const ReplayParams& params, const RippleParams& ripple,
                     std::span<const SliceSampler> samplers)
    : m_identity(rippleIsIdentity(ripple)) {
    ModeParams mode;
    mode.mode = ReplayMode::Ripple;
    mode.ripple = ripple;
    mode.validate();
    checkSamplers(mode, samplers);
    const int D = static_cast<int>(ripple.anglesDegrees.size());
    for (int d = 0; d < D; ++d) {
        m_dirs.push_back(std::make_unique<GpuReplay>(frames, sliceSetParams(params, d),
                                                     samplers[static_cast<std::size_t>(d)]));
        m_uploadedBytes += m_dirs.back()->uploadedBytes();
    }
    if (m_identity)
        return; // one direction at 0 degrees: its own field is the result, no synthesis pass

    const Grid& g = grid();
    const int N = g.cellsX;
    const int M = g.cellsZ;
    const std::size_t cells = static_cast<std::size_t>(N) * static_cast<std::size_t>(M);
    // Per direction (cos a_d, sin a_d, omega_d): the shader maps each cell itself.
    const std::vector<double> omega = ripple.normalisedWeights();
    std::vector<float> dirs;
    for (int d = 0; d < D; ++d) {
        const double a =
            ripple.anglesDegrees[static_cast<std::size_t>(d)] * std::numbers::pi / 180.0;
        for (double v : {std::cos(a), std::sin(a), omega[static_cast<std::size_t>(d)], 0.0})
            dirs.push_back(static_cast<float>(v));
    }
    if (static_cast<double>(D) * static_cast<double>(cells) > 2147483647.0)
        throw RuntimeError("the ripple synthesis addresses more than 2^31 heights: lower --res");
    m_directionTable = makeStorageBuffer(dirs.size() * sizeof(float), dirs.data());
    m_dirHeights = makeStorageBuffer(static_cast<std::size_t>(D) * cells * sizeof(float), nullptr);
    m_out = std::make_unique<HeightOutput>(N, M);
    m_synthesis = makeEmbeddedProgram("ripple_synthesis.comp");
    const GLuint sp = m_synthesis.get();
    glProgramUniform1i(sp, uniformLocation(m_synthesis, "u_N"), N);
    glProgramUniform1i(sp, uniformLocation(m_synthesis, "u_M"), M);
    glProgramUniform1i(sp, uniformLocation(m_synthesis, "u_D"), D);
    glProgramUniform1f(sp, uniformLocation(m_synthesis, "u_cx"), static_cast<float>(0.5 * N));
    glProgramUniform1f(sp, uniformLocation(m_synthesis, "u_cz"), static_cast<float>(0.5 * M));
    glProgramUniform1f(sp, uniformLocation(m_synthesis, "u_dzdx"), static_cast<float>(g.dz / g.dx));
    glProgramUniform1f(sp, uniformLocation(m_synthesis, "u_edgeMargin"),
                       static_cast<float>(kRippleEdgeMargin * g.cellsX));
    glProgramUniform1f(sp, uniformLocation(m_synthesis, "u_edgeFloor"),
                       static_cast<float>(kRippleEdgeFloor));
    for (GlQuery& q : m_queries)
        q = makeTimestampQuery();
    checkGl("setting up the ripple synthesis");
}

void GpuRipple::setTiming(bool on) {
    m_timing = on;
    for (auto& r : m_dirs)
        r->setTiming(on);
}

void GpuRipple::update(double tau) {
    m_timed = m_timing;
    for (auto& r : m_dirs)
        r->update(tau); // Algorithm 2b, steps 3-8: eq. (5)-(7) per direction
    if (m_identity)
        return;
    // Gather the directions' fields into one buffer (GpuReplay's barrier covers the copy).
    const Grid& g = grid();
    const auto bytes = static_cast<GLsizeiptr>(static_cast<std::size_t>(g.cellsX) *
                                               static_cast<std::size_t>(g.cellsZ) * sizeof(float));
    if (m_timing)
        glQueryCounter(m_queries[0].get(), GL_TIMESTAMP);
    for (std::size_t d = 0; d < m_dirs.size(); ++d) {
        glCopyNamedBufferSubData(m_dirs[d]->heightBuffer(), m_dirHeights.get(), 0,
                                 static_cast<GLintptr>(d) * bytes, bytes);
    }
    // Step 9, eq. (8).
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m_dirHeights.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m_directionTable.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m_out->buffer());
    glUseProgram(m_synthesis.get());
    glDispatchCompute((static_cast<GLuint>(g.cellsX) + kGroup - 1) / kGroup,
                      static_cast<GLuint>(g.cellsZ), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_PIXEL_BUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    if (m_timing)
        glQueryCounter(m_queries[1].get(), GL_TIMESTAMP);
    m_out->markWritten();
}

StageTimes GpuRipple::stageTimes() const {
    if (!m_timed)
        throw std::logic_error("GpuRipple::stageTimes: no timed update yet");
    StageTimes t;
    for (const auto& r : m_dirs)
        t += r->stageTimes();
    if (!m_identity)
        t.synthesisMs = elapsedMs(m_queries[0], m_queries[1]);
    return t;
}

std::vector<const GpuReplay*> GpuRipple::sliceSets() const {
    std::vector<const GpuReplay*> out;
    for (const auto& d : m_dirs)
        out.push_back(d.get());
    return out;
}

GlName GpuRipple::heightBuffer() const {
    return m_identity ? m_dirs.front()->heightBuffer() : m_out->buffer();
}

GlName GpuRipple::heightTexture() {
    return m_identity ? m_dirs.front()->heightTexture() : m_out->texture();
}

HeightField GpuRipple::readHeights() const {
    return m_identity ? m_dirs.front()->readHeights() : m_out->read();
}

} // namespace swell::runtime
