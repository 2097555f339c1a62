#pragma once
// Small RAII owners of GL object names and the shader-program builder. Every function needs
// a current context (EglContext).

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <utility>

namespace swell::runtime {

using GlName = std::uint32_t; ///< a GLuint

/// Owns one GL object name; `Deleter` frees it.
template <void (*Deleter)(GlName)> class GlHandle {
public:
    GlHandle() = default;
    explicit GlHandle(GlName name) : m_name(name) {}
    ~GlHandle() { reset(); }
    GlHandle(GlHandle&& o) noexcept : m_name(std::exchange(o.m_name, 0)) {}
    GlHandle& operator=(GlHandle&& o) noexcept {
        if (this != &o) {
            reset();
            m_name = std::exchange(o.m_name, 0);
        }
        return *this;
    }
    GlHandle(const GlHandle&) = delete;
    GlHandle& operator=(const GlHandle&) = delete;

    GlName get() const { return m_name; }
    void reset() {
        if (m_name != 0)
            Deleter(m_name);
        m_name = 0;
    }

private:
    GlName m_name = 0;
};

void deleteGlBuffer(GlName name);
void deleteGlProgram(GlName name);
void deleteGlTexture(GlName name);
void deleteGlQuery(GlName name);

using GlBuffer = GlHandle<deleteGlBuffer>;
using GlProgram = GlHandle<deleteGlProgram>;
using GlTexture = GlHandle<deleteGlTexture>;
using GlQuery = GlHandle<deleteGlQuery>;

/// A shader-storage buffer of `bytes` bytes, filled from `data` (may be null).
GlBuffer makeStorageBuffer(std::size_t bytes, const void* data);
/// Compiles and links one compute shader. Throws RuntimeError with the driver's log, naming
/// the shader.
GlProgram makeComputeProgram(std::string_view name, std::string_view source);
/// Compiles and links the embedded shader `name` (shaders/<name>).
GlProgram makeEmbeddedProgram(std::string_view name);

/// Location of a uniform the shader must have; a missing one is a bug (std::logic_error).
int uniformLocation(const GlProgram& program, const char* name);
/// A GL_TIMESTAMP query. Timestamps, not GL_TIME_ELAPSED: llvmpipe reports elapsed time 0
/// for compute dispatches, while timestamps work there and on GPU drivers alike.
GlQuery makeTimestampQuery();
/// Milliseconds between two written timestamp queries (waits for their results).
double elapsedMs(const GlQuery& from, const GlQuery& to);
/// Throws RuntimeError naming `what` if glGetError reports an error.
void checkGl(std::string_view what);

} // namespace swell::runtime
