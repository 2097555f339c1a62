#pragma once
// The output of a mode replay (ripple synthesis, whirlpool mapping): an SSBO of N x M floats,
// [m * N + n] = height in metres at the centre of cell (n, m), plus an R32F texture copy made on
// the GPU when first asked after each write (the same layout as GpuReplay's heightBuffer()).

#include "swell/runtime/gl/gl_objects.h"
#include "swell/runtime/replay/height_field.h"

namespace swell::runtime {

class HeightOutput {
public:
    /// Allocates the buffer and the texture (linear filtering, clamp to edge). Needs a context.
    HeightOutput(int cellsX, int cellsZ);

    GlName buffer() const { return m_buffer.get(); }
    /// The texture copy of buffer(), refreshed if the buffer was written since the last call.
    GlName texture();
    /// Call after a pass wrote buffer().
    void markWritten() { m_stale = true; }
    /// Reads the heights back (blocks).
    HeightField read() const;

private:
    int m_N;
    int m_M;
    GlBuffer m_buffer;
    GlTexture m_texture;
    bool m_stale = true;
};

} // namespace swell::runtime
