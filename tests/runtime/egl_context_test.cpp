#include "swell/runtime/egl_context.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <gtest/gtest.h>

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
