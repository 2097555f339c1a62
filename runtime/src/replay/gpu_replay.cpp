#include "swell/runtime/replay/gpu_replay.h"

#include "swell/runtime/parallel_chunks.h"

#include "swell/runtime/error.h"
#include "swell/runtime/replay/cpu_reconstruction.h"
#include "swell/runtime/replay/surface_envelope.h"
#include "swell/shaders/shaders.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <stdexcept>
#include <string>

namespace swell::runtime {
namespace {

constexpr GLuint kGroup1D = 64;      // local_size_x of column_pass.comp
constexpr GLuint kGroupLookup = 256; // local_size_x of slice_lookup.comp

GLuint groups(long long count, GLuint size) {
    return static_cast<GLuint>((count + size - 1) / size);
}

/// The surface particles of every held frame as (u, h - reference), u = (x - x0) / dx, sorted
/// by x bin b = floor(u) (-1 .. N; others are beyond every window), and per frame the N + 3
/// offsets of its bins: the inputs of column_pass.comp.
void packParticles(const FrameSet& frames, const Grid& grid, double reference,
                   std::vector<float>& particles, std::vector<GLuint>& binStart) {
    const int N = grid.cellsX;
    binStart.reserve(frames.frames.size() * static_cast<std::size_t>(N + 3));
    std::vector<int> binOf;
    std::vector<GLuint> fill;
    for (const cache::Frame& f : frames.frames) {
        const std::size_t P = f.surfaceCount();
        binOf.assign(P, 0);
        fill.assign(static_cast<std::size_t>(N + 2), 0);
        for (std::size_t p = 0; p < P; ++p) {
            const double u = (static_cast<double>(f.surface[2 * p]) - grid.x0) / grid.dx;
            const double b = std::floor(u);
            binOf[p] = b < -1.0 || b > N ? -2 : static_cast<int>(b); // -2: beyond every window
            if (binOf[p] >= -1)
                ++fill[static_cast<std::size_t>(binOf[p] + 1)];
        }
        GLuint running = static_cast<GLuint>(particles.size() / 2);
        for (int b = -1; b <= N; ++b) {
            binStart.push_back(running);
            const GLuint c = fill[static_cast<std::size_t>(b + 1)];
            fill[static_cast<std::size_t>(b + 1)] = running; // now the write cursor
            running += c;
        }
        binStart.push_back(running);
        particles.resize(2 * static_cast<std::size_t>(running));
        for (std::size_t p = 0; p < P; ++p) {
            if (binOf[p] < -1)
                continue;
            const GLuint at = fill[static_cast<std::size_t>(binOf[p] + 1)]++;
            const double u = (static_cast<double>(f.surface[2 * p]) - grid.x0) / grid.dx;
            particles[2 * at] = static_cast<float>(u);
            particles[2 * at + 1] =
                static_cast<float>(static_cast<double>(f.surface[2 * p + 1]) - reference);
        }
    }
}

/// The held slot of cache frame `id`, or -1 when `frames` does not hold it.
long long heldSlot(const FrameSet& frames, std::uint32_t id) {
    const cache::Frame* f = frames.find(id);
    return f == nullptr ? -1 : static_cast<long long>(f - frames.frames.data());
}

/// Per timeline entry, its column slot and its shown frame (the inputs of slice_lookup.comp).
struct SlotTable {
    std::vector<std::size_t> blendEntries; ///< timeline entries with a cross-fade slot, in order
    std::vector<GLuint> slotOf;            ///< column slot, or 0xffffffff when not held
    std::vector<GLint> shown;              ///< the cache frame shown
};

/// Slots of the column buffer: the held frames, then one per cross-faded timeline entry whose
/// two frames are both held (timeline.h).
SlotTable assignSlots(const FrameSet& frames, const Timeline& timeline, std::size_t entries) {
    const std::size_t held = frames.frames.size();
    SlotTable t;
    t.slotOf.assign(entries, 0xffffffffu);
    t.shown.assign(entries, 0);
    for (std::size_t i = 0; i < entries; ++i) {
        const TimelineEntry& e = timeline[i];
        t.shown[i] = static_cast<GLint>(e.shown());
        const long long a = heldSlot(frames, e.a);
        if (!e.blended()) {
            if (a >= 0)
                t.slotOf[i] = static_cast<GLuint>(a);
        } else if (a >= 0 && heldSlot(frames, e.b) >= 0) {
            t.slotOf[i] = static_cast<GLuint>(held + t.blendEntries.size());
            t.blendEntries.push_back(i);
        }
    }
    return t;
}

/// reconstruct.comp runs one work group per row, as few groups as fit the row's column quads:
/// the quads per group, a power of two in 32 .. 256.
std::uint32_t reconstructQuadsPerGroup(int N) {
    const GLuint quads = static_cast<GLuint>((N + 3) / 4);
    std::uint32_t perGroup = 32;
    while (perGroup < quads && perGroup < 256)
        perGroup *= 2;
    return perGroup;
}

/// reconstruct.comp compiled for `quadsPerGroup` column quads per work group.
GlProgram makeReconstructProgram(std::uint32_t quadsPerGroup) {
    std::string source(shaders::get("reconstruct.comp"));
    source.insert(source.find('\n') + 1,
                  fmt::format("#define SWELL_QUADS_PER_GROUP {}\n", quadsPerGroup));
    return makeComputeProgram("reconstruct.comp", source);
}

/// Throws RuntimeError when the particle or column buffer exceeds the driver's limit of one
/// shader-storage block.
void checkStorageLimit(std::size_t particleBytes, std::size_t columnBytes, std::size_t heldFrames,
                       int N) {
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    for (const std::size_t bytes : {particleBytes, columnBytes}) {
        if (static_cast<GLint64>(bytes) > maxBlock) {
            throw RuntimeError(fmt::format(
                "the replay needs a {:.0f} MB buffer ({} held frames at {} columns), above this "
                "driver's {:.0f} MB shader-storage limit: lower --res or replay fewer seconds",
                static_cast<double>(bytes) / 1e6, heldFrames, N,
                static_cast<double>(maxBlock) / 1e6));
        }
    }
}

/// Float index of h (c = 0) or W (c = 1) of column n in `slot` of the column buffer, whose
/// slots hold Nq column quads (column_pass.comp).
std::size_t columnIndex(int Nq, std::size_t slot, int n, int c) {
    return ((slot * static_cast<std::size_t>(Nq) + static_cast<std::size_t>(n / 4)) * 2 +
            static_cast<std::size_t>(c)) *
               4 +
           static_cast<std::size_t>(n % 4);
}

/// Envelope columns (eta(P_x), 1), or (empty-frame height `missing`, 0), of every held frame
/// on the CPU in double, heights relative to `reference`, into `columns`. Returns the time
/// taken (ms).
double sampleEnvelopeColumns(const FrameSet& frames, const Grid& grid, double reference,
                             float missing, std::vector<float>& columns) {
    const auto t0 = std::chrono::steady_clock::now();
    const int N = grid.cellsX;
    const int Nq = (N + 3) / 4;
    const std::size_t held = frames.frames.size();
    const double binWidth = envelopeBinWidth(frames.header, grid);
    // Each slot writes only its own columns: split over the cores.
    forEachChunk(held, chunkCount(held, 64), [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t slot = begin; slot < end; ++slot) {
            const std::vector<double> eta =
                sampleEnvelope(SurfaceEnvelope(frames.frames[slot], binWidth), grid.x0, grid.dx, N);
            for (int n = 0; n < N; ++n) {
                columns[columnIndex(Nq, slot, n, 0)] =
                    eta.empty() ? missing
                                : static_cast<float>(eta[static_cast<std::size_t>(n)] - reference);
                columns[columnIndex(Nq, slot, n, 1)] = eta.empty() ? 0.0f : 1.0f;
            }
        }
    });
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// Cross-fades of two held frames' columns (blendColumns), once: reads the held frames' columns
/// of `columnBuffer` into `columns` and uploads the cross-faded slots that follow them.
void uploadCrossFades(GLuint columnBuffer, const FrameSet& frames, const Timeline& timeline,
                      const std::vector<std::size_t>& blendEntries, int N,
                      std::vector<float>& columns) {
    const int Nq = (N + 3) / 4;
    const std::size_t held = frames.frames.size();
    glGetNamedBufferSubData(columnBuffer, 0, static_cast<GLsizeiptr>(held * Nq * 8 * sizeof(float)),
                            columns.data());
    for (std::size_t b = 0; b < blendEntries.size(); ++b) {
        const TimelineEntry& e = timeline[blendEntries[b]];
        const auto sa = static_cast<std::size_t>(heldSlot(frames, e.a));
        const auto sb = static_cast<std::size_t>(heldSlot(frames, e.b));
        const std::size_t slot = held + b;
        for (int n = 0; n < N; ++n) {
            // The buffer holds (h, W); blendColumns takes (h W, W), or (h, 0) when W = 0.
            auto sum = [&](std::size_t s, int k) {
                const double h = columns[columnIndex(Nq, s, k, 0)];
                const double W = columns[columnIndex(Nq, s, k, 1)];
                return W > 0.0 ? ColumnSum{h * W, W} : ColumnSum{h, 0.0};
            };
            const ColumnSum c = blendColumns(sum(sa, n), sum(sb, n), e.alpha);
            columns[columnIndex(Nq, slot, n, 0)] = static_cast<float>(c.height());
            columns[columnIndex(Nq, slot, n, 1)] = static_cast<float>(c.W);
        }
    }
    const std::size_t offset = held * static_cast<std::size_t>(Nq) * 8;
    glNamedBufferSubData(columnBuffer, static_cast<GLintptr>(offset * sizeof(float)),
                         static_cast<GLsizeiptr>((columns.size() - offset) * sizeof(float)),
                         columns.data() + offset);
    checkGl("uploading the cross-faded columns");
}

} // namespace

GpuReplay::GpuReplay(const FrameSet& frames, const ReplayParams& params,
                     const SliceSampler& sampler)
    : m_grid(makeGrid(frames.header, params)), m_A(sampler.A()), m_F(sampler.fluctuation()),
      m_T(params.noise.timeSamples), m_loop(sampler.policy() != FramePolicy::Clamp),
      m_timelineSize(sampler.timeline().size()) {
    params.validate();
    frames.validate();
    const Timeline& timeline = sampler.timeline();
    if (timeline.maxFrame() >= frames.frameCount || sampler.sliceCount() != m_grid.sliceCount()) {
        throw std::logic_error("GpuReplay: sampler and frame set disagree");
    }
    const int N = m_grid.cellsX;
    m_heldFrames = frames.frames.size();
    const SlotTable table = assignSlots(frames, timeline, m_timelineSize);
    m_slots = m_heldFrames + table.blendEntries.size();

    m_lookup = makeEmbeddedProgram("slice_lookup.comp");
    m_quadsPerGroup = reconstructQuadsPerGroup(N);
    m_reconstruct = makeReconstructProgram(m_quadsPerGroup);
    const bool envelope = params.reconstruction == Reconstruction::Envelope;

    // Heights are uploaded relative to the middle of the domain, which keeps float sums of
    // eq. (7) accurate; it depends on the header only, so the result does not depend on which
    // frames are held.
    const double reference =
        0.5 * (static_cast<double>(frames.header.domain.yMin) + frames.header.domain.yMax);
    m_reference = static_cast<float>(reference);
    m_missing = static_cast<float>(frames.header.domain.yMin - reference);

    // ---- paper: particles sorted by x bin (-1 .. N), one bin index per held frame
    const std::size_t S = std::max<std::size_t>(m_slots, 1);
    std::vector<float> particles;
    std::vector<GLuint> binStart;
    if (!envelope) // the envelope's columns come from the CPU: no particles on the GPU
        packParticles(frames, m_grid, reference, particles, binStart);
    if (m_heldFrames == 0 || envelope)
        binStart.assign(static_cast<std::size_t>(N + 3), 0);
    const std::size_t columnBytes = S * static_cast<std::size_t>((N + 3) / 4) * 8 * sizeof(float);
    checkStorageLimit(particles.size() * sizeof(float), columnBytes, m_heldFrames, N);
    const int Nq = (N + 3) / 4; // columns in quads of four (column_pass.comp)
    std::vector<float> zeros(S * static_cast<std::size_t>(Nq) * 8, 0.0f);
    for (GlQuery& q : m_queries)
        q = makeTimestampQuery();
    if (envelope)
        m_columnPassMs = sampleEnvelopeColumns(frames, m_grid, reference, m_missing, zeros);
    m_columns = makeStorageBuffer(zeros.size() * sizeof(float), zeros.data());
    if (!envelope)
        runColumnPass(particles, binStart, params.sigma);
    if (!table.blendEntries.empty())
        uploadCrossFades(m_columns.get(), frames, timeline, table.blendEntries, N, zeros);
    buildLookupAndRows(params, sampler, table.slotOf, table.shown);
    m_uploadedBytes = particles.size() * sizeof(float) + binStart.size() * sizeof(GLuint) +
                      zeros.size() * sizeof(float) +
                      table.slotOf.size() * (sizeof(GLuint) + sizeof(GLint)) + m_lookupBytes;
    glFinish(); // the particle and bin buffers are released when this returns
    checkGl("uploading the replay");
}

void GpuReplay::runColumnPass(const std::vector<float>& particles,
                              const std::vector<GLuint>& binStart, double sigma) {
    const int N = m_grid.cellsX;
    const int Nq = (N + 3) / 4;
    GlProgram column = makeEmbeddedProgram("column_pass.comp");
    GlBuffer particleBuffer = makeStorageBuffer(particles.size() * sizeof(float), particles.data());
    GlBuffer binBuffer = makeStorageBuffer(binStart.size() * sizeof(GLuint), binStart.data());
    // ---- column pass: x half of eq. (7) per held frame and column, once
    glProgramUniform1i(column.get(), uniformLocation(column, "u_N"), N);
    glProgramUniform1i(column.get(), uniformLocation(column, "u_Nq"), Nq);
    glProgramUniform1i(column.get(), uniformLocation(column, "u_slots"),
                       static_cast<GLint>(m_heldFrames));
    const GLint slotBase = uniformLocation(column, "u_slotBase");
    glProgramUniform1f(column.get(), uniformLocation(column, "u_sigma"), static_cast<float>(sigma));
    glProgramUniform1f(column.get(), uniformLocation(column, "u_emptyHeight"), m_missing);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particleBuffer.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, binBuffer.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m_columns.get());
    if (m_heldFrames > 0) {
        glUseProgram(column.get());
        glQueryCounter(m_queries[0].get(), GL_TIMESTAMP);
        // One work-group row per held frame, in batches of the driver's rows per dispatch
        // (65,535 at least): long caches can hold more frames than that.
        GLint maxRows = 0;
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 1, &maxRows);
        const auto batch = static_cast<std::size_t>(std::max(maxRows, 1));
        for (std::size_t first = 0; first < m_heldFrames; first += batch) {
            glProgramUniform1i(column.get(), slotBase, static_cast<GLint>(first));
            glDispatchCompute(groups(N, kGroup1D),
                              static_cast<GLuint>(std::min(batch, m_heldFrames - first)), 1);
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glQueryCounter(m_queries[1].get(), GL_TIMESTAMP);
        m_columnPassMs = elapsedMs(m_queries[0], m_queries[1]);
    }
    glFinish();
    checkGl("running the column pass");
}

void GpuReplay::buildLookupAndRows(const ReplayParams& params, const SliceSampler& sampler,
                                   const std::vector<GLuint>& slotOf,
                                   const std::vector<GLint>& shown) {
    const int N = m_grid.cellsX;
    const int M = m_grid.cellsZ;
    const int K = m_grid.slices;
    const int J = m_grid.sliceCount();
    const int Nq = (N + 3) / 4;
    // ---- slice lookup inputs: noise (fp64), timeline entry -> column slot and shown frame
    const FbmNoise* noise = sampler.noise();
    std::vector<double> noiseValues = noise ? noise->values() : std::vector<double>{0.0};
    m_noise = makeStorageBuffer(noiseValues.size() * sizeof(double), noiseValues.data());
    m_slotOf = makeStorageBuffer(slotOf.size() * sizeof(GLuint), slotOf.data());
    m_shown = makeStorageBuffer(shown.size() * sizeof(GLint), shown.data());
    m_slices = makeStorageBuffer(static_cast<std::size_t>(J) * 2 * sizeof(GLint), nullptr);
    m_blend = makeStorageBuffer(static_cast<std::size_t>(J) * 2 * sizeof(float), nullptr);
    const GLuint lp = m_lookup.get();
    m_lookupTau = uniformLocation(m_lookup, "u_tau");
    glProgramUniform1d(lp, uniformLocation(m_lookup, "u_F"), m_F);
    glProgramUniform1d(lp, uniformLocation(m_lookup, "u_A"), m_A);
    glProgramUniform1i(lp, uniformLocation(m_lookup, "u_T"), noise ? noise->timeSamples() : 1);
    glProgramUniform1i(lp, uniformLocation(m_lookup, "u_K"), K);
    glProgramUniform1i(lp, uniformLocation(m_lookup, "u_sliceCount"), J);
    glProgramUniform1i(lp, uniformLocation(m_lookup, "u_frameCount"),
                       static_cast<GLint>(m_timelineSize));
    glProgramUniform1i(lp, uniformLocation(m_lookup, "u_loop"), m_loop ? 1 : 0);
    glProgramUniform1i(lp, uniformLocation(m_lookup, "u_linear"),
                       sampler.timeSampling() == TimeSampling::Linear ? 1 : 0);

    // ---- z windows: first slice, count and G_z per row (definitions: cpu_reconstruction.h)
    std::vector<GLint> rows(2 * static_cast<std::size_t>(M));
    std::vector<std::vector<float>> rowWeights(static_cast<std::size_t>(M));
    const double inv2s2 = 1.0 / (2.0 * params.sigma * params.sigma);
    for (int m = 0; m < M; ++m) {
        // -2K <= (j + 1) M - (2m + 1) K < 2K  <=>  (2m - 1) K <= (j + 1) M < (2m + 3) K
        const long long lo = static_cast<long long>(2 * m - 1) * K;
        const long long hi = static_cast<long long>(2 * m + 3) * K;
        int first = -1, last = -1;
        for (int j = 0; j < J; ++j) {
            const long long v = static_cast<long long>(j + 1) * M;
            if (v >= lo && v < hi) {
                if (first < 0)
                    first = j;
                last = j;
            }
        }
        if (first < 0) { // no slice in the window (M > 2K): the nearest one, ties to the lower j
            const long long target = static_cast<long long>(2 * m + 1) * K;
            first = 0;
            for (int j = 1; j < J; ++j) {
                if (std::llabs(static_cast<long long>(j + 1) * M - target) <
                    std::llabs(static_cast<long long>(first + 1) * M - target)) {
                    first = j;
                }
            }
            last = first;
        }
        rows[2 * static_cast<std::size_t>(m)] = first;
        rows[2 * static_cast<std::size_t>(m) + 1] = last - first + 1;
        for (int j = first; j <= last; ++j) {
            // A row of one slice (always so when M > 2K) has G_z = 1: it cancels in eq. (7),
            // and far from the slice exp() underflows to 0, which made 0 / 0 = NaN heights
            // (found by tools/stress at 1 x 4096 cells, K = 64).
            const double dz = first == last ? 0.0 : m_grid.sliceZCells(j) - (m + 0.5);
            rowWeights[static_cast<std::size_t>(m)].push_back(
                static_cast<float>(std::exp(-dz * dz * inv2s2)));
        }
        m_rowStride = std::max(m_rowStride, last - first + 1);
    }
    std::vector<float> weights(static_cast<std::size_t>(M) * static_cast<std::size_t>(m_rowStride),
                               0.0f);
    for (int m = 0; m < M; ++m) {
        std::copy(rowWeights[static_cast<std::size_t>(m)].begin(),
                  rowWeights[static_cast<std::size_t>(m)].end(),
                  weights.begin() + static_cast<std::ptrdiff_t>(m) * m_rowStride);
    }
    m_rows = makeStorageBuffer(rows.size() * sizeof(GLint), rows.data());
    m_weights = makeStorageBuffer(weights.size() * sizeof(float), weights.data());
    const GLuint rp = m_reconstruct.get();
    glProgramUniform1i(rp, uniformLocation(m_reconstruct, "u_N"), N);
    glProgramUniform1i(rp, uniformLocation(m_reconstruct, "u_Nq"), Nq);
    glProgramUniform1i(rp, uniformLocation(m_reconstruct, "u_M"), M);
    glProgramUniform1i(rp, uniformLocation(m_reconstruct, "u_rowStride"), m_rowStride);
    glProgramUniform1f(rp, uniformLocation(m_reconstruct, "u_reference"), m_reference);
    glProgramUniform1f(rp, uniformLocation(m_reconstruct, "u_missing"), m_missing);

    m_out.emplace(N, M);

    m_lookupBytes = noiseValues.size() * sizeof(double) + rows.size() * sizeof(GLint) +
                    weights.size() * sizeof(float);
}

void GpuReplay::update(double tau) {
    lookupSlices(tau);
    // Pass 2, eq. (7): every cell from the column sums of the slices in its z window.
    reconstructHeights();
}

void GpuReplay::lookupSlices(double tau) {
    if (!std::isfinite(tau) || (std::abs(tau) + 1.0) * m_A > 1.0e9) {
        throw std::invalid_argument(
            fmt::format("animation time tau = {} is out of range for A = {}", tau, m_A));
    }
    m_timedUpdate = m_timing;
    // Pass 1, eq. (5)-(6): the frame of every slice, once per slice.
    glProgramUniform1d(m_lookup.get(), m_lookupTau, tau);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m_noise.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m_slotOf.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m_slices.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m_shown.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m_blend.get());
    glUseProgram(m_lookup.get());
    if (m_timing)
        glQueryCounter(m_queries[0].get(), GL_TIMESTAMP);
    glDispatchCompute(groups(m_grid.sliceCount(), kGroupLookup), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (m_timing)
        glQueryCounter(m_queries[1].get(), GL_TIMESTAMP);
}

void GpuReplay::reconstructHeights() {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m_slices.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m_columns.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m_rows.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m_weights.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, m_out->buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, m_blend.get());
    glUseProgram(m_reconstruct.get());
    glDispatchCompute(groups((m_grid.cellsX + 3) / 4, m_quadsPerGroup),
                      static_cast<GLuint>(m_grid.cellsZ), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_PIXEL_BUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    m_out->markWritten();
    if (m_timing)
        glQueryCounter(m_queries[2].get(), GL_TIMESTAMP);
}

StageTimes GpuReplay::stageTimes() const {
    if (!m_timedUpdate)
        throw std::logic_error("GpuReplay::stageTimes: no timed update yet");
    StageTimes t;
    t.sliceLookupMs = elapsedMs(m_queries[0], m_queries[1]);
    t.reconstructMs = elapsedMs(m_queries[1], m_queries[2]);
    return t;
}

void GpuReplay::finish() const {
    glFinish();
}

std::vector<std::uint32_t> GpuReplay::readSliceFrames() const {
    std::vector<GLint> pairs(2 * static_cast<std::size_t>(m_grid.sliceCount()));
    glGetNamedBufferSubData(m_slices.get(), 0,
                            static_cast<GLsizeiptr>(pairs.size() * sizeof(GLint)), pairs.data());
    checkGl("reading the slice frames back");
    std::vector<std::uint32_t> out(static_cast<std::size_t>(m_grid.sliceCount()));
    for (std::size_t j = 0; j < out.size(); ++j)
        out[j] = static_cast<std::uint32_t>(pairs[2 * j]);
    return out;
}

} // namespace swell::runtime
