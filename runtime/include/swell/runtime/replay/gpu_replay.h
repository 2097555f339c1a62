#pragma once
// The replay on the GPU (compute shaders, GL 4.5): eq. (5)-(6) slice lookup and eq. (7)
// reconstruction into an R32F height texture. Needs a current GL context (EglContext).
//
// Construction uploads the held frames once: surface particles sorted by x bin with a per-frame
// bin index (so a column reads only its own 3 bins), and runs the column pass: the x half of
// the separable eq. (7) sums, per frame and column (shaders/column_pass.comp). Each update(tau)
// then runs two small passes, no upload and no readback:
//   1. slice_lookup.comp: s_j for the 2K - 1 slices (fp64, matches SliceSampler exactly);
//   2. reconstruct.comp: each cell combines the column sums of the slices in its z window,
//      into a float buffer (heightBuffer(); a texture copy on request, heightTexture()).
// Definitions of the window and the fallback: cpu_reconstruction.h.

#include "swell/runtime/gl/gl_objects.h"
#include "swell/runtime/replay/frame_set.h"
#include "swell/runtime/replay/height_field.h"
#include "swell/runtime/replay/height_output.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/replay/slice_sampler.h"
#include "swell/runtime/stage_times.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace swell::runtime {

class GpuReplay {
public:
    /// Uploads `frames` and runs the column pass. `sampler` supplies the noise, A and the policy
    /// (it is not kept). Throws std::invalid_argument (parameters) or RuntimeError (GL).
    GpuReplay(const FrameSet& frames, const ReplayParams& params, const SliceSampler& sampler);

    /// Computes the height field at animation time tau on the GPU; returns without waiting.
    /// Slices whose frame is not held read as the domain's yMin (hold every frame that
    /// SliceSampler::framesUsed names for the taus you play).
    void update(double tau);
    /// Pass 1 of update() only: eq. (5)-(6) into sliceBuffer(), no height field (the whirlpool
    /// maps the column sums itself). stageTimes() is not defined after it alone.
    void lookupSlices(double tau);
    /// Puts a GL timestamp query around each pass of update() (adds a little overhead).
    void setTiming(bool on) { m_timing = on; }
    /// Stage times of the last timed update() (slice lookup, reconstruct); waits for the GPU.
    StageTimes stageTimes() const;
    /// Time of the one-off column pass at construction (ms): GPU timer query (paper), or the
    /// CPU envelope sampling (envelope).
    double columnPassMs() const { return m_columnPassMs; }
    /// Blocks until every command issued so far has finished (glFinish).
    void finish() const;

    /// SSBO of N x M floats, [m * N + n] = the height (metres, cache y) at the centre of cell
    /// (n, m), x = x0 + (n + 1/2) dx, z = (m + 1/2) dz: what update() writes. Bind it as a
    /// shader-storage buffer or as a GL_TEXTURE_BUFFER (R32F) for texelFetch.
    GlName heightBuffer() const { return m_out->buffer(); }
    /// The same heights as an R32F 2D texture (N x M, linear filtering, clamp to edge) for
    /// sampling: copied from heightBuffer() on the first call after each update(), on the GPU.
    GlName heightTexture() { return m_out->texture(); }
    /// SSBO of 2K - 1 ivec2: (cache frame shown, column slot or -1) of slice j, at z_j.
    GlName sliceBuffer() const { return m_slices.get(); }
    /// SSBO of 2K - 1 vec2: (second column slot or -1, its weight) of slice j: the slice
    /// shows mix(slot of sliceBuffer(), this slot, weight) (TimeSampling::Linear; weight 0
    /// with Nearest).
    GlName blendBuffer() const { return m_blend.get(); }
    /// Reads the heights back (blocks).
    HeightField readHeights() const { return m_out->read(); }
    /// Reads the frame of every slice back (blocks).
    std::vector<std::uint32_t> readSliceFrames() const;

    /// SSBO of the column pass (column_pass.comp): per held-frame slot and column quad
    /// q = n / 4, a vec4 of S (or the fallback) then a vec4 of W, heights relative to
    /// referenceHeight(); float index ((slot * columnQuads() + q) * 2 + c) * 4 + n % 4.
    GlName columnBuffer() const { return m_columns.get(); }
    int columnQuads() const { return (m_grid.cellsX + 3) / 4; }
    /// Level subtracted from the uploaded heights (metres).
    float referenceHeight() const { return m_reference; }
    /// Relative height of a slice whose frame is not held (the domain's yMin).
    float missingHeight() const { return m_missing; }

    const Grid& grid() const { return m_grid; }
    std::size_t heldFrames() const { return m_heldFrames; }
    /// Slots of columnBuffer(): the held frames, then the cross-faded timeline entries.
    std::size_t slotCount() const { return m_slots; }
    /// Bytes uploaded at construction (particles, bin index, column sums, tables).
    std::size_t uploadedBytes() const { return m_uploadedBytes; }
    /// The slice sets of this replay: itself (the same call on every mode, mode_replay.h).
    std::vector<const GpuReplay*> sliceSets() const { return {this}; }

private:
    void reconstructHeights();
    /// column_pass.comp over the held frames' particles (Reconstruction::Paper).
    void runColumnPass(const std::vector<float>& particles, const std::vector<unsigned>& binStart,
                       double sigma);
    /// Slice-lookup tables (noise, entry -> slot, entry -> shown frame) and the z windows.
    void buildLookupAndRows(const ReplayParams& params, const SliceSampler& sampler,
                            const std::vector<unsigned>& slotOf, const std::vector<int>& shown);

    Grid m_grid;
    double m_A;
    double m_F;
    int m_T;
    bool m_loop;
    std::size_t m_timelineSize; ///< entries of the sampler's timeline
    std::size_t m_heldFrames = 0;
    std::size_t m_slots = 0;
    std::size_t m_lookupBytes = 0;
    std::size_t m_uploadedBytes = 0;
    float m_reference = 0.0f;
    float m_missing = 0.0f;
    int m_rowStride = 0;
    std::uint32_t m_quadsPerGroup = 32;
    bool m_timing = false;
    bool m_timedUpdate = false;
    double m_columnPassMs = 0.0;

    GlProgram m_lookup;
    GlProgram m_reconstruct;
    GlBuffer m_noise;
    GlBuffer m_slotOf;
    GlBuffer m_shown;
    GlBuffer m_slices;
    GlBuffer m_blend; ///< per slice j: (second column slot, weight), slice_lookup.comp
    GlBuffer m_columns;
    GlBuffer m_rows;
    GlBuffer m_weights;
    std::optional<HeightOutput> m_out; ///< the heights (made once the parameters are checked)
    GlQuery m_queries[3];
    int m_lookupTau = -1;
};

} // namespace swell::runtime
