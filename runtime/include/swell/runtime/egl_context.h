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
    /// Makes this context current on the calling thread.
    void makeCurrent() const;

private:
    void* m_display = nullptr;
    void* m_context = nullptr;
    std::string m_renderer;
    std::string m_version;
    std::string m_platform;
};

} // namespace swell::runtime
