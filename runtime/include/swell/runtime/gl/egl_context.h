#pragma once
// A headless OpenGL 4.5 core context through EGL, with no display and no window (Filament's
// PlatformEGLHeadless): the EGL device platform on a real GPU, else Mesa's surfaceless
// platform (llvmpipe on machines without a GPU). Current on the creating thread.

#include <string>

namespace swell::runtime {

class EglContext {
public:
    /// Creates the context and makes it current. Throws RuntimeError (no EGL, no usable
    /// device, no GL 4.5 core context).
    EglContext();
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    /// GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    const std::string& renderer() const { return m_renderer; }
    /// GL_VERSION.
    const std::string& version() const { return m_version; }
    /// "device" (EGL_EXT_platform_device) or "surfaceless" (EGL_MESA_platform_surfaceless).
    const std::string& platform() const { return m_platform; }
    /// Makes this context current on the calling thread (nothing to do when it is).
    void makeCurrent() const;
    /// llvmpipe's rasteriser threads (LP_NUM_THREADS) when the context was made; 0 if unset
    /// (one per core) or the renderer is not llvmpipe.
    int llvmpipeThreads() const { return m_llvmpipeThreads; }

private:
    void* m_display = nullptr;
    void* m_context = nullptr;
    std::string m_renderer;
    std::string m_version;
    std::string m_platform;
    int m_llvmpipeThreads = 0;
};

/// Free video memory of the current context's GPU in KiB (GL_NVX_gpu_memory_info, NVIDIA
/// drivers), or -1 where the driver does not report it (Mesa). Differences before and after
/// an allocation measure what it took on the device.
long long freeVideoMemoryKiB();

/// Checks that the calling thread has a current GL 4.5 (or later) context, e.g. an
/// application's own; returns its GL_VERSION. Throws RuntimeError saying what is missing.
std::string requireCurrentContext();

/// Mesa's llvmpipe (the software rasteriser used where there is no GPU) sets up each draw on
/// the calling thread and rasterises it in 64 x 64 pixel tiles on LP_NUM_THREADS threads, by
/// default one per core. With one thread more than cores, a core whose thread has run out of
/// tiles picks up the extra thread's, which renders faster on few cores (figures:
/// docs/BENCHMARKS.md, "Render"). Sets LP_NUM_THREADS to cores + 1 unless it is already set; call
/// it before the first EglContext (Mesa reads it once). Returns the value in effect.
int preferLlvmpipeThreads();

} // namespace swell::runtime
