#include "swell/runtime/gl/gl_objects.h"

#include "swell/runtime/gl/graphics_program.h"

#include "swell/runtime/error.h"
#include "swell/shaders/shaders.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <fmt/format.h>
#include <stdexcept>
#include <string>

namespace swell::runtime {

void deleteGlBuffer(GlName name) {
    glDeleteBuffers(1, &name);
}
void deleteGlProgram(GlName name) {
    glDeleteProgram(name);
}
void deleteGlTexture(GlName name) {
    glDeleteTextures(1, &name);
}
void deleteGlQuery(GlName name) {
    glDeleteQueries(1, &name);
}

GlBuffer makeStorageBuffer(std::size_t bytes, const void* data) {
    GlName name = 0;
    glCreateBuffers(1, &name);
    GlBuffer buffer(name);
    // Zero-sized storage is not allowed; keep one word so bindings stay valid.
    glNamedBufferStorage(name, static_cast<GLsizeiptr>(bytes == 0 ? 4 : bytes),
                         bytes == 0 ? nullptr : data, GL_DYNAMIC_STORAGE_BIT);
    checkGl("creating a shader-storage buffer");
    return buffer;
}

GlProgram makeComputeProgram(std::string_view name, std::string_view source) {
    // A .comp name: the compute stage.
    return linkProgram({compileShader(name, source)}, fmt::format("shader {} does not link", name));
}

GlProgram makeEmbeddedProgram(std::string_view name) {
    return makeComputeProgram(name, shaders::get(name));
}

void checkGl(std::string_view what) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        throw RuntimeError(fmt::format("OpenGL error 0x{:x} while {}", error, what));
    }
}

int uniformLocation(const GlProgram& program, const char* name) {
    const GLint loc = glGetUniformLocation(program.get(), name);
    if (loc < 0)
        throw std::logic_error(fmt::format("shader uniform {} not found", name));
    return loc;
}

GlQuery makeTimestampQuery() {
    GLuint q = 0;
    glCreateQueries(GL_TIMESTAMP, 1, &q);
    return GlQuery(q);
}

double elapsedMs(const GlQuery& from, const GlQuery& to) {
    GLuint64 a = 0, b = 0;
    glGetQueryObjectui64v(from.get(), GL_QUERY_RESULT, &a);
    glGetQueryObjectui64v(to.get(), GL_QUERY_RESULT, &b);
    return static_cast<double>(b - a) * 1e-6;
}

} // namespace swell::runtime
