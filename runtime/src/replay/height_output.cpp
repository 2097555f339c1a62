#include "swell/runtime/replay/height_output.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <vector>

namespace swell::runtime {

HeightOutput::HeightOutput(int cellsX, int cellsZ)
    : m_N(cellsX), m_M(cellsZ),
      m_buffer(makeStorageBuffer(static_cast<std::size_t>(cellsX) *
                                     static_cast<std::size_t>(cellsZ) * sizeof(float),
                                 nullptr)) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    m_texture = GlTexture(tex);
    glTextureStorage2D(tex, 1, GL_R32F, m_N, m_M);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    checkGl("creating the height output");
}

GlName HeightOutput::texture() {
    if (m_stale) {
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, m_buffer.get());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(m_texture.get(), 0, 0, 0, m_N, m_M, GL_RED, GL_FLOAT, nullptr);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        checkGl("copying the heights into the height texture");
        m_stale = false;
    }
    return m_texture.get();
}

HeightField HeightOutput::read() const {
    HeightField out;
    out.cellsX = m_N;
    out.cellsZ = m_M;
    std::vector<float> texels(static_cast<std::size_t>(m_N) * static_cast<std::size_t>(m_M));
    glGetNamedBufferSubData(m_buffer.get(), 0,
                            static_cast<GLsizeiptr>(texels.size() * sizeof(float)), texels.data());
    checkGl("reading the height field back");
    out.heights.assign(texels.begin(), texels.end());
    return out;
}

} // namespace swell::runtime
