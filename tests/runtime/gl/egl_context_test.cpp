#include "swell/runtime/gl/egl_context.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <thread>

namespace swell::runtime {

TEST(EglContext, CreatesHeadlessGl45CoreContext) {
    EglContext context;
    EXPECT_FALSE(context.renderer().empty());
    EXPECT_TRUE(context.platform() == "device" || context.platform() == "surfaceless");
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45) << context.version();
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    RecordProperty("renderer", context.renderer());
    std::printf("renderer: %s (%s, EGL %s)\n", context.renderer().c_str(),
                context.version().c_str(), context.platform().c_str());
}

TEST(EglContext, TwoContextsLiveInOneProcess) {
    EglContext a;
    EglContext b; // current now
    GLint v = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &v);
    EXPECT_GE(v, 4);
    a.makeCurrent();
    glGetIntegerv(GL_MAJOR_VERSION, &v);
    EXPECT_GE(v, 4);
    EXPECT_EQ(a.renderer(), b.renderer());
}

TEST(EglContext, RendersAComputeResultThatReadsBack) {
    // A context that "works" but computes nothing (a known headless-EGL failure) fails here.
    EglContext context;
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    const GLuint data[4] = {1, 2, 3, 4};
    glNamedBufferStorage(buffer, sizeof(data), data, GL_DYNAMIC_STORAGE_BIT);
    const char* src = "#version 450 core\nlayout(local_size_x = 4) in;\n"
                      "layout(std430, binding = 0) buffer B { uint v[]; };\n"
                      "void main() { v[gl_LocalInvocationID.x] *= 10u; }\n";
    GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &src, nullptr);
    glCompileShader(shader);
    GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glUseProgram(program);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint out[4] = {};
    glGetNamedBufferSubData(buffer, 0, sizeof(out), out);
    EXPECT_EQ(out[0], 10u);
    EXPECT_EQ(out[3], 40u);
    glDeleteProgram(program);
    glDeleteShader(shader);
    glDeleteBuffers(1, &buffer);
}

} // namespace swell::runtime

TEST(EglContext, LlvmpipeRunsOneRasteriserThreadMoreThanCoresUnlessTold) {
    const char* before = std::getenv("LP_NUM_THREADS");
    const std::string saved = before != nullptr ? before : "";
    const int cores = static_cast<int>(std::max(std::thread::hardware_concurrency(), 1u));
    ::unsetenv("LP_NUM_THREADS");
    EXPECT_EQ(swell::runtime::preferLlvmpipeThreads(), cores + 1);
    EXPECT_EQ(std::string(std::getenv("LP_NUM_THREADS")), std::to_string(cores + 1));
    // The user's setting wins.
    ::setenv("LP_NUM_THREADS", "5", 1);
    EXPECT_EQ(swell::runtime::preferLlvmpipeThreads(), 5);
    EXPECT_EQ(std::string(std::getenv("LP_NUM_THREADS")), "5");
    {
        const swell::runtime::EglContext context;
        if (context.renderer().find("llvmpipe") != std::string::npos)
            EXPECT_EQ(context.llvmpipeThreads(), 5);
        else
            EXPECT_EQ(context.llvmpipeThreads(), 0);
    }
    if (before != nullptr)
        ::setenv("LP_NUM_THREADS", saved.c_str(), 1);
    else
        ::unsetenv("LP_NUM_THREADS");
}
