#include "swell/runtime/gl/graphics_program.h"

#include "swell/runtime/error.h"
#include "swell/shaders/shaders.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <fmt/format.h>
#include <stdexcept>
#include <string>

namespace swell::runtime {
namespace {

std::string shaderLog(GLuint shader) {
    std::string log(4096, '\0');
    GLsizei n = 0;
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), &n, log.data());
    log.resize(static_cast<std::size_t>(n));
    while (!log.empty() && (log.back() == '\n' || log.back() == '\0'))
        log.pop_back();
    return log;
}

} // namespace

GlName compileShader(std::string_view name, std::string_view source) {
    const GLuint shader = glCreateShader(shaderStageOf(name));
    const char* text = source.data();
    const GLint length = static_cast<GLint>(source.size());
    glShaderSource(shader, 1, &text, &length);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = shaderLog(shader);
        glDeleteShader(shader);
        throw RuntimeError(fmt::format("shader {} does not compile: {}", name, log));
    }
    return shader;
}

std::uint32_t shaderStageOf(std::string_view name) {
    if (name.ends_with(".vert"))
        return GL_VERTEX_SHADER;
    if (name.ends_with(".frag"))
        return GL_FRAGMENT_SHADER;
    if (name.ends_with(".comp"))
        return GL_COMPUTE_SHADER;
    throw std::logic_error(fmt::format("no shader stage for file name {}", name));
}

void checkShaderCompiles(std::string_view name, std::string_view source) {
    glDeleteShader(compileShader(name, source));
}

GlProgram makeGraphicsProgram(std::string_view vertexName, std::string_view fragmentName) {
    const GLuint vs = compileShader(vertexName, shaders::get(vertexName));
    GLuint fs = 0;
    try {
        fs = compileShader(fragmentName, shaders::get(fragmentName));
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    return linkProgram({vs, fs},
                       fmt::format("shaders {} + {} do not link", vertexName, fragmentName));
}

GlProgram linkProgram(std::initializer_list<GlName> shaders, std::string_view what) {
    GlProgram program(glCreateProgram());
    for (const GlName s : shaders)
        glAttachShader(program.get(), s);
    glLinkProgram(program.get());
    for (const GlName s : shaders)
        glDeleteShader(s);
    GLint ok = 0;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        std::string log(4096, '\0');
        GLsizei n = 0;
        glGetProgramInfoLog(program.get(), static_cast<GLsizei>(log.size()), &n, log.data());
        log.resize(static_cast<std::size_t>(n));
        throw RuntimeError(fmt::format("{}: {}", what, log));
    }
    return program;
}

} // namespace swell::runtime
