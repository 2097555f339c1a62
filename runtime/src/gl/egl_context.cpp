#include "swell/runtime/gl/egl_context.h"

#include "swell/runtime/error.h"

#define GL_GLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <string>
#include <thread>
#include <vector>

namespace swell::runtime {
namespace {

bool hasExtension(const char* list, const char* name) {
    if (list == nullptr)
        return false;
    const std::size_t len = std::strlen(name);
    for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + len, name)) {
        if ((p == list || p[-1] == ' ') && (p[len] == ' ' || p[len] == '\0'))
            return true;
    }
    return false;
}

/// A display on the first hardware EGL device (not Mesa's software device), or none.
EGLDisplay deviceDisplay() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(client, "EGL_EXT_platform_device"))
        return EGL_NO_DISPLAY;
    auto queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        eglGetProcAddress("eglQueryDeviceStringEXT"));
    if (queryDevices == nullptr || queryString == nullptr)
        return EGL_NO_DISPLAY;
    EGLint count = 0;
    if (queryDevices(0, nullptr, &count) != EGL_TRUE || count <= 0)
        return EGL_NO_DISPLAY;
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    queryDevices(count, devices.data(), &count);
    for (EGLDeviceEXT device : devices) {
        if (hasExtension(queryString(device, EGL_EXTENSIONS), "EGL_MESA_device_software"))
            continue;
        EGLDisplay d = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
        EGLint major = 0, minor = 0;
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor) == EGL_TRUE)
            return d;
    }
    return EGL_NO_DISPLAY;
}

} // namespace

EglContext::EglContext() {
    EGLDisplay display = deviceDisplay();
    m_platform = "device";
    if (display == EGL_NO_DISPLAY) {
        m_platform = "surfaceless";
        display =
            eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (display == EGL_NO_DISPLAY || eglInitialize(display, &major, &minor) != EGL_TRUE) {
            throw RuntimeError(
                fmt::format("no usable EGL display: no GPU device and no Mesa surfaceless platform "
                            "(EGL error 0x{:x}; install libegl-mesa0 and libgl1-mesa-dri)",
                            eglGetError()));
        }
    }
    m_display = display;
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
        throw RuntimeError("EGL cannot bind the desktop OpenGL API");
    }
    // Surfaceless contexts need EGL_KHR_no_config_context (Mesa, NVIDIA both have it).
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT) {
        const EGLint error = eglGetError();
        throw RuntimeError(fmt::format(
            "cannot create an OpenGL 4.5 core context on the EGL {} platform (EGL error 0x{:x})",
            m_platform, error));
    }
    m_context = context;
    if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
        const EGLint error = eglGetError();
        eglDestroyContext(display, context);
        throw RuntimeError(
            fmt::format("cannot make the GL context current (EGL error 0x{:x})", error));
    }
    m_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    m_version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    const char* threads = std::getenv("LP_NUM_THREADS");
    if (threads != nullptr && m_renderer.find("llvmpipe") != std::string::npos)
        m_llvmpipeThreads = std::atoi(threads);
}

int preferLlvmpipeThreads() {
    if (const char* set = std::getenv("LP_NUM_THREADS"))
        return std::atoi(set);
    const int threads = static_cast<int>(std::max(std::thread::hardware_concurrency(), 1u)) + 1;
    ::setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 0);
    return threads;
}

EglContext::~EglContext() {
    if (eglGetCurrentContext() == m_context) {
        eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(m_display, m_context);
    // eglTerminate is not called: displays are shared per process (EGL 1.5), and terminating
    // one would pull it from under another context in the same process.
}

void EglContext::makeCurrent() const {
    if (eglGetCurrentContext() == m_context)
        return;
    if (eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_context) != EGL_TRUE) {
        throw RuntimeError(
            fmt::format("cannot make the GL context current (EGL error 0x{:x})", eglGetError()));
    }
}

} // namespace swell::runtime

namespace swell::runtime {

long long freeVideoMemoryKiB() {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto* name =
            reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
        if (name != nullptr && std::strcmp(name, "GL_NVX_gpu_memory_info") == 0) {
            constexpr GLenum kCurrentAvailableVidmemNvx = 0x9049; // GL_NVX_gpu_memory_info
            GLint kib = 0;
            glGetIntegerv(kCurrentAvailableVidmemNvx, &kib);
            return kib;
        }
    }
    return -1;
}

std::string requireCurrentContext() {
    // Without a current context a GL call does nothing (libglvnd) and glGetString gives null.
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    if (version == nullptr)
        throw RuntimeError("no GL context is current on this thread (the caller's context was "
                           "asked for: make a GL 4.5 core context current first)");
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        throw RuntimeError(fmt::format(
            "the current GL context is {} (GL_VERSION '{}'): the replay needs GL 4.5 with compute "
            "shaders",
            fmt::format("{}.{}", major, minor), version));
    return version;
}

} // namespace swell::runtime
