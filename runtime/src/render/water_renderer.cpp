#include "swell/runtime/render/water_renderer.h"

#include "swell/runtime/error.h"
#include "swell/runtime/gl/graphics_program.h"
#include "swell/runtime/render/mesh_order.h"
#include "swell/runtime/render/splash_culling.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace swell::runtime {
namespace {

// Uniform locations shared by the shaders (layout(location = ...) in shaders/*.vert|frag).
constexpr GLint kViewProj = 0, kCells = 1, kOrigin = 2, kSpacing = 3, kEye = 4, kSunDir = 5,
                kBedY = 6, kAbsorption = 7, kScatter = 8, kBed = 9, kEta = 10, kF0 = 11, kSun = 12,
                kSunColour = 13, kEdge = 14, kPixelsPerMetre = 15, kRadius = 16, kSplashColour = 17,
                kReflectionLod = 18, kAmbient = 19, kDropLight = 20, kSideLight = 21, kFloor = 22,
                kBlock = 23, kBlockTop = 24, kFirstRow = 25, kRows = 26;
/// Bytes of one mesh vertex (surface_vertices.comp's Vertex: three vec4).
constexpr GLsizei kVertexBytes = 3 * 4 * sizeof(float);

void setVec3(GLuint program, GLint loc, const Vec3& v) {
    glProgramUniform3f(program, loc, static_cast<float>(v[0]), static_cast<float>(v[1]),
                       static_cast<float>(v[2]));
}

bool finiteColour(const Vec3& v) {
    return std::all_of(v.begin(), v.end(), [](double c) { return std::isfinite(c) && c >= 0.0; });
}

} // namespace

void FloorParams::validate() const {
    if (!(tileSize > 0.0) || !std::isfinite(tileSize))
        throw std::invalid_argument(fmt::format("floor tile size must be > 0 m, got {}", tileSize));
    if (!(tileContrast >= 0.0 && tileContrast <= 1.0)) {
        throw std::invalid_argument(
            fmt::format("floor tile contrast must be in [0, 1], got {}", tileContrast));
    }
    if (!(hazeDistance > 0.0) || !std::isfinite(hazeDistance)) {
        throw std::invalid_argument(
            fmt::format("floor haze distance must be > 0 m, got {}", hazeDistance));
    }
}

void ShadingParams::validate() const {
    if (width < 16 || height < 16 || width > 8192 || height > 8192) {
        throw std::invalid_argument(
            fmt::format("image size must be within 16..8192 pixels, got {}x{}", width, height));
    }
    if (vertexRowsPerDispatch < 0)
        throw std::invalid_argument(fmt::format(
            "vertex rows per dispatch must be >= 0 (0: no limit), got {}", vertexRowsPerDispatch));
    if (samples < 1 || samples > 16)
        throw std::invalid_argument(fmt::format("samples must be in 1..16, got {}", samples));
    if (!(refractiveIndex >= 1.0 && refractiveIndex < 3.0)) {
        throw std::invalid_argument(
            fmt::format("refractive index must be in [1, 3), got {}", refractiveIndex));
    }
    if (!finiteColour(absorption) || !finiteColour(scatterColour) || !finiteColour(bedColour) ||
        !finiteColour(sunColour) || !finiteColour(splashColour)) {
        throw std::invalid_argument("shading colours and absorption must be finite and >= 0");
    }
    if (!(reflectionLod >= 0.0) || !std::isfinite(reflectionLod))
        throw std::invalid_argument("reflection LOD must be >= 0");
    if (!(sunShininess >= 1.0) || !(sunIntensity >= 0.0) || !std::isfinite(sunShininess) ||
        !std::isfinite(sunIntensity)) {
        throw std::invalid_argument("sun shininess must be >= 1 and intensity >= 0");
    }
    floor.validate();
}

WaterRenderer::WaterRenderer(const Grid& grid, const cache::Domain& domain,
                             const ShadingParams& shading, const CubeFaces& sky, const Vec3& sun)
    : m_grid(grid), m_domain(domain), m_shading(shading), m_sun(sun) {
    shading.validate();
    if (grid.cellsX < 2 || grid.cellsZ < 2)
        throw std::invalid_argument("the mesh needs at least 2 x 2 cells");
    m_skyProgram = makeGraphicsProgram("sky.vert", "sky.frag");
    m_waterProgram = makeGraphicsProgram("water.vert", "water.frag");
    m_surfaceProgram = makeEmbeddedProgram("surface_vertices.comp");
    m_skirtProgram = makeGraphicsProgram("skirt.vert", "skirt.frag");
    m_splashProgram = makeGraphicsProgram("splash.vert", "splash.frag");
    m_backgroundProgram = makeGraphicsProgram("sky.vert", "background.frag");
    m_sky = makeCubemapTexture(sky);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);

    createMeshBuffers();
    createFramebuffers();
    for (GlQuery& q : m_queries)
        q = makeTimestampQuery();
    setSurfaceUniforms();
    setLightUniforms(sky);
    checkGl("setting up the water renderer");
}

void WaterRenderer::checkMeshFits(int cellsX, int cellsZ) {
    GLint64 maxBlock = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    const auto heightBytes =
        static_cast<GLint64>(cellsX) * cellsZ * static_cast<GLint64>(sizeof(float));
    if (heightBytes > maxBlock) {
        const double cells = std::floor(static_cast<double>(maxBlock) / sizeof(float));
        throw std::invalid_argument(fmt::format(
            "cells_x x cells_z must fit this driver's {:.0f} MB shader-storage block, 4 bytes a "
            "cell: at most {:.0f} cells (about {:.0f}x{:.0f}), got {}x{}",
            static_cast<double>(maxBlock) / 1e6, cells, std::floor(std::sqrt(cells)),
            std::floor(std::sqrt(cells)), cellsX, cellsZ));
    }
}

void WaterRenderer::writeVertices() {
    const int N = m_grid.cellsX, M = m_grid.cellsZ;
    const GLuint program = m_surfaceProgram.get();
    for (int first = 0; first < M; first += m_rowsPerDispatch) {
        const int rows = std::min(m_rowsPerDispatch, M - first);
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, m_vertices.get(),
                          static_cast<GLintptr>(first) * N * kVertexBytes,
                          static_cast<GLsizeiptr>(rows) * N * kVertexBytes);
        glProgramUniform1i(program, kFirstRow, first);
        glProgramUniform1i(program, kRows, rows);
        glDispatchCompute((static_cast<GLuint>(N) * static_cast<GLuint>(rows) + 63) / 64, 1, 1);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

void WaterRenderer::createMeshBuffers() {
    // Triangles of the N x M vertex grid (vertex id m * N + n), reordered front to back for
    // each new eye point (updateMeshOrder).
    const int N = m_grid.cellsX, M = m_grid.cellsZ;
    m_indexCount = static_cast<std::size_t>(N - 1) * static_cast<std::size_t>(M - 1) * 6;
    GLuint name = 0;
    glCreateBuffers(1, &name);
    m_indices = GlBuffer(name);
    glNamedBufferStorage(name, static_cast<GLsizeiptr>(m_indexCount * sizeof(std::uint32_t)),
                         nullptr, GL_DYNAMIC_STORAGE_BIT);
    // The mesh's vertices, written by surface_vertices.comp each frame: position, reflected
    // view ray, shaded colour and Fresnel weight, three vec4 per vertex; as many rows per
    // dispatch as one shader-storage block holds, starting at aligned offsets (writeVertices).
    // The heights the pass reads are bound whole: their 4 bytes per cell set the limit.
    checkMeshFits(N, M);
    GLint64 maxBlock = 0;
    GLint align = 1;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
    const GLint64 alignment = std::max<GLint64>(align, 1);
    const GLint64 rowBytes = static_cast<GLint64>(N) * kVertexBytes;
    const GLint64 rowStep = alignment / std::gcd(rowBytes, alignment); // rows per aligned offset
    const GLint64 fit = maxBlock / rowBytes / rowStep * rowStep;
    if (fit < 1)
        throw RuntimeError(fmt::format("a mesh row of {} cells exceeds this driver's {:.0f} MB "
                                       "shader-storage limit (lower --res)",
                                       N, static_cast<double>(maxBlock) / 1e6));
    m_rowsPerDispatch = static_cast<int>(std::min<GLint64>(fit, M));
    if (m_shading.vertexRowsPerDispatch > 0)
        m_rowsPerDispatch = std::min(m_rowsPerDispatch, m_shading.vertexRowsPerDispatch);
    glCreateBuffers(1, &name);
    m_vertices = GlBuffer(name);
    glNamedBufferStorage(name, static_cast<GLsizeiptr>(N) * M * kVertexBytes, nullptr, 0);
    glCreateVertexArrays(1, &m_meshArray);
    glVertexArrayElementBuffer(m_meshArray, m_indices.get());
    glVertexArrayVertexBuffer(m_meshArray, 0, m_vertices.get(), 0, kVertexBytes);
    for (GLuint attribute = 0; attribute < 3; ++attribute) {
        glEnableVertexArrayAttrib(m_meshArray, attribute);
        glVertexArrayAttribFormat(m_meshArray, attribute, 4, GL_FLOAT, GL_FALSE,
                                  attribute * 4 * sizeof(float));
        glVertexArrayAttribBinding(m_meshArray, attribute, 0);
    }
    glCreateVertexArrays(1, &m_vertexArray); // no attributes: full-screen passes, the sides

    glCreateBuffers(1, &name);
    m_splashBuffer = GlBuffer(name);
    glCreateVertexArrays(1, &m_splashArray);
    glEnableVertexArrayAttrib(m_splashArray, 0);
    glVertexArrayAttribFormat(m_splashArray, 0, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(m_splashArray, 0, 0);
}

void WaterRenderer::createFramebuffers() {
    // Offscreen framebuffers: multisampled colour + depth, resolved into a plain colour buffer.
    GLint maxSamples = 1;
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    m_samples = std::max(1, std::min(m_shading.samples, static_cast<int>(maxSamples)));
    glCreateRenderbuffers(3, m_renderbuffers);
    const int W = m_shading.width, H = m_shading.height;
    glNamedRenderbufferStorageMultisample(m_renderbuffers[0], m_samples > 1 ? m_samples : 0,
                                          GL_SRGB8_ALPHA8, W, H);
    glNamedRenderbufferStorageMultisample(m_renderbuffers[1], m_samples > 1 ? m_samples : 0,
                                          GL_DEPTH24_STENCIL8, W, H);
    glNamedRenderbufferStorage(m_renderbuffers[2], GL_SRGB8_ALPHA8, W, H);
    glCreateFramebuffers(1, &m_msFramebuffer);
    glNamedFramebufferRenderbuffer(m_msFramebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                   m_renderbuffers[0]);
    glNamedFramebufferRenderbuffer(m_msFramebuffer, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                   m_renderbuffers[1]);
    glCreateFramebuffers(1, &m_framebuffer);
    glNamedFramebufferRenderbuffer(m_framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                   m_renderbuffers[2]);
    GLuint bg = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &bg);
    m_background = GlTexture(bg);
    glTextureStorage2D(bg, 1, GL_SRGB8_ALPHA8, W, H);
    glCreateFramebuffers(1, &m_backgroundFramebuffer);
    glNamedFramebufferTexture(m_backgroundFramebuffer, GL_COLOR_ATTACHMENT0, bg, 0);
    for (GLuint fb : {m_msFramebuffer, m_framebuffer, m_backgroundFramebuffer}) {
        const GLenum status = glCheckNamedFramebufferStatus(fb, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            throw RuntimeError(
                fmt::format("offscreen framebuffer {}x{} ({} samples) incomplete: 0x{:x}", W, H,
                            m_samples, status));
        }
    }
}

void WaterRenderer::setSurfaceUniforms() {
    const ShadingParams& shading = m_shading;
    const int N = m_grid.cellsX, M = m_grid.cellsZ;
    const float eta = static_cast<float>(1.0 / shading.refractiveIndex);
    const double r = (shading.refractiveIndex - 1.0) / (shading.refractiveIndex + 1.0);
    const auto f0 = static_cast<float>(r * r);
    const float bedY = m_domain.yMin;
    for (GLuint p : {m_surfaceProgram.get(), m_skirtProgram.get()}) {
        glProgramUniform2i(p, kCells, N, M);
        glProgramUniform2f(p, kOrigin, static_cast<float>(m_grid.x0 + 0.5 * m_grid.dx),
                           static_cast<float>(0.5 * m_grid.dz));
        glProgramUniform2f(p, kSpacing, static_cast<float>(m_grid.dx),
                           static_cast<float>(m_grid.dz));
        glProgramUniform1f(p, kBedY, bedY);
        setVec3(p, kAbsorption, shading.absorption);
        setVec3(p, kScatter, shading.scatterColour);
    }
    const GLuint v = m_surfaceProgram.get();
    setVec3(v, kSunDir, m_sun);
    setVec3(v, kBed, shading.bedColour);
    glProgramUniform1f(v, kEta, eta);
    glProgramUniform1f(v, kF0, f0);
    glProgramUniform1f(v, kReflectionLod, static_cast<float>(shading.reflectionLod));
    glProgramUniform1f(m_skirtProgram.get(), kF0, f0);
    // The floor, drawn with the sky (sky.frag): the bed's colour and lighting, the block's
    // footprint (the mesh's extent, as the sides) for its shadow.
    const GLuint f = m_skyProgram.get();
    setVec3(f, kSunDir, m_sun);
    glProgramUniform1f(f, kBedY, bedY);
    setVec3(f, kAbsorption, shading.absorption);
    setVec3(f, kBed, shading.bedColour);
    glProgramUniform4f(f, kFloor, static_cast<float>(shading.floor.tileSize),
                       static_cast<float>(shading.floor.tileContrast),
                       static_cast<float>(shading.floor.hazeDistance),
                       shading.floor.enabled ? 1.0f : 0.0f);
    const MeshLayout mesh = meshLayout();
    glProgramUniform4f(f, kBlock, static_cast<float>(mesh.x0), static_cast<float>(mesh.z0),
                       static_cast<float>(mesh.x0 + (N - 1) * mesh.dx),
                       static_cast<float>(mesh.z0 + (M - 1) * mesh.dz));
}

void WaterRenderer::setLightUniforms(const CubeFaces& sky) {
    const Vec3& sun = m_sun;
    const GLuint w = m_waterProgram.get();
    setVec3(w, kSunDir, sun);
    glProgramUniform2f(w, kSun, static_cast<float>(m_shading.sunShininess),
                       static_cast<float>(m_shading.sunIntensity));
    setVec3(w, kSunColour, m_shading.sunColour);
    const Vec3 ambient = zenithRadiance(sky);
    // Light from above entering a side: the sky straight up and the sun, tinted by the water.
    const double sideLight = 0.6 * (0.35 + 0.65 * std::max(sun[1], 0.0));
    const Vec3 sideTint{0.55, 0.85, 0.9};
    setVec3(m_skirtProgram.get(), kSideLight,
            {ambient[0] * sideLight * sideTint[0], ambient[1] * sideLight * sideTint[1],
             ambient[2] * sideLight * sideTint[2]});
    setVec3(m_splashProgram.get(), kAmbient, ambient);
    Vec3 dropLight{sun[0], sun[1], sun[2] + 0.5};
    const double dropNorm = std::hypot(dropLight[0], dropLight[1], dropLight[2]);
    for (double& c : dropLight)
        c /= dropNorm;
    setVec3(m_splashProgram.get(), kDropLight, dropLight);
    setVec3(m_splashProgram.get(), kSplashColour, m_shading.splashColour);
}

WaterRenderer::~WaterRenderer() {
    glDeleteFramebuffers(1, &m_backgroundFramebuffer);
    glDeleteFramebuffers(1, &m_framebuffer);
    glDeleteFramebuffers(1, &m_msFramebuffer);
    glDeleteRenderbuffers(3, m_renderbuffers);
    glDeleteVertexArrays(1, &m_splashArray);
    glDeleteVertexArrays(1, &m_vertexArray);
    glDeleteVertexArrays(1, &m_meshArray);
}

void WaterRenderer::stamp(const GlQuery& query) const {
    if (!m_timing)
        return;
    // llvmpipe rasterises a whole scene when it is flushed and writes a timestamp when the
    // scene holding it has been rasterised: the query would be charged with the draws issued
    // after it. Finishing before and after puts each timestamp in a scene of its own, between
    // the stages (a timed frame is serialised stage by stage and a little slower).
    glFinish();
    glQueryCounter(query.get(), GL_TIMESTAMP);
    glFinish();
}

void WaterRenderer::draw(GlName heightBuffer, const Camera& camera,
                         std::span<const SplashSprite> splashes, double splashRadius) {
    drawSurface(heightBuffer, camera, !splashes.empty());
    drawSplashes(splashes, splashRadius);
}

void WaterRenderer::drawSurface(GlName heightBuffer, const Camera& camera, bool splashesFollow) {
    camera.validate();
    const int W = m_shading.width, H = m_shading.height;
    const Mat4 viewProj = viewProjection(camera);
    const Mat4 invViewProj = inverse(viewProj);
    const auto& eye = camera.position;
    m_frameCamera = camera;

    const bool sameCamera = m_backgroundValid && m_backgroundCamera.position == camera.position &&
                            m_backgroundCamera.target == camera.target &&
                            m_backgroundCamera.fovYDegrees == camera.fovYDegrees;
    if (!sameCamera)
        renderBackground(camera, invViewProj, heightBuffer);
    if (!m_indexValid || m_indexEye != eye)
        updateMeshOrder(eye);

    m_heightsValid = false;
    if (splashesFollow) {
        // For culling the drops under the surface (drawSplashes). The heights are read before
        // anything is drawn: once a draw reading them (the sides) is in flight, llvmpipe would
        // wait for it to be rasterised before mapping the buffer.
        m_heights.resize(static_cast<std::size_t>(m_grid.cellsX) * m_grid.cellsZ);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(heightBuffer, 0,
                                static_cast<GLsizeiptr>(m_heights.size() * sizeof(float)),
                                m_heights.data());
        m_heightsValid = true;
    }
    // 1. Environment: the cached sky pass, copied (a texel-fetch pass when multisampled: a copy
    //    or a framebuffer blit cannot write a multisampled target).
    stamp(m_queries[0]);
    glEnable(GL_FRAMEBUFFER_SRGB); // shaders write linear RGB; the colour buffers are sRGB
    glBindFramebuffer(GL_FRAMEBUFFER, m_msFramebuffer);
    glViewport(0, 0, W, H);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    // Depth and stencil are cleared together (llvmpipe's fast path; a depth-only clear, or
    // writing the far depth from the background pass, measured several times slower).
    glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glBindVertexArray(m_vertexArray);
    if (m_samples == 1) {
        // A plain copy (a memcpy on llvmpipe: no sRGB decoding and encoding per pixel).
        glCopyImageSubData(m_background.get(), GL_TEXTURE_2D, 0, 0, 0, 0, m_renderbuffers[0],
                           GL_RENDERBUFFER, 0, 0, 0, 0, W, H, 1);
    } else {
        glDisable(GL_DEPTH_TEST);
        glBindTextureUnit(1, m_background.get());
        glUseProgram(m_backgroundProgram.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glBindTextureUnit(0, m_sky.get());
    stamp(m_queries[1]);

    // 2. The height field (Sec. 5) and the sides of the block.
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, heightBuffer);
    for (GLuint p : {m_surfaceProgram.get(), m_skirtProgram.get()})
        setVec3(p, kEye, eye);
    for (GLuint p : {m_waterProgram.get(), m_skirtProgram.get()}) {
        glProgramUniformMatrix4fv(p, kViewProj, 1, GL_FALSE, viewProj.data());
    }
    glUseProgram(m_surfaceProgram.get());
    writeVertices();
    glUseProgram(m_waterProgram.get());
    glBindVertexArray(m_meshArray);
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(m_indexCount), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(m_vertexArray);
    if (m_shading.sides) {
        glUseProgram(m_skirtProgram.get());
        const std::array<bool, 4> sides = visibleSides(meshLayout(), m_domain.yMin, eye);
        for (int edge = 0; edge < 4; ++edge) {
            if (!sides[static_cast<std::size_t>(edge)])
                continue;
            glProgramUniform1i(m_skirtProgram.get(), kEdge, edge);
            glDrawArrays(GL_TRIANGLE_STRIP, 0, 2 * (edge < 2 ? m_grid.cellsX : m_grid.cellsZ));
        }
    }
    // Hand the sky and water to llvmpipe's rasteriser threads now: they shade them while this
    // thread goes on (the caller builds the splash sprites; their vertex processing and set-up
    // run on this thread).
    glFlush();
    stamp(m_queries[2]);
    m_surfaceDrawn = true;
    checkGl("drawing the water");
}

void WaterRenderer::drawSplashes(std::span<const SplashSprite> splashes, double splashRadius) {
    if (!m_surfaceDrawn)
        throw std::logic_error("WaterRenderer::drawSplashes without drawSurface");
    m_surfaceDrawn = false;
    const int W = m_shading.width, H = m_shading.height;
    m_lastSplashes = splashes.size();
    m_lastCulled = 0;
    m_visibleSprites.clear();
    if (!splashes.empty()) {
        if (!m_heightsValid) {
            throw std::logic_error(
                "WaterRenderer::drawSplashes: drawSurface was told no splashes follow");
        }
        // Drops under the (opaque) surface are invisible: skip their vertex and set-up work.
        m_lastCulled = cullSubmergedSplashes(
            splashes, m_heights, m_grid,
            {splashRadius, m_frameCamera.position, pixelsPerMetre(m_frameCamera)},
            m_visibleSprites);
    }
    // 3. Splash point sprites (Sec. 5), blended over the water, depth tested, not written.
    glBindFramebuffer(GL_FRAMEBUFFER, m_msFramebuffer);
    if (!m_visibleSprites.empty()) {
        const std::span<const SplashSprite> visible(m_visibleSprites);
        const auto bytes = static_cast<GLsizeiptr>(visible.size_bytes());
        if (visible.size() > m_splashCapacity) {
            m_splashCapacity = visible.size() + visible.size() / 2;
            glNamedBufferData(m_splashBuffer.get(),
                              static_cast<GLsizeiptr>(m_splashCapacity * sizeof(SplashSprite)),
                              nullptr, GL_STREAM_DRAW);
        }
        glNamedBufferSubData(m_splashBuffer.get(), 0, bytes, visible.data());
        glVertexArrayVertexBuffer(m_splashArray, 0, m_splashBuffer.get(), 0, sizeof(SplashSprite));
        const GLuint p = m_splashProgram.get();
        glProgramUniformMatrix4fv(p, kViewProj, 1, GL_FALSE, viewProjection(m_frameCamera).data());
        glProgramUniform1f(p, kPixelsPerMetre, static_cast<float>(pixelsPerMetre(m_frameCamera)));
        glProgramUniform1f(p, kRadius, static_cast<float>(splashRadius));
        glEnable(GL_PROGRAM_POINT_SIZE);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA); // premultiplied alpha
        glDepthMask(GL_FALSE);
        glUseProgram(p);
        glBindVertexArray(m_splashArray);
        glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(visible.size()));
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
    }
    stamp(m_queries[3]);

    // 4. Resolve the multisampled picture (without multisampling, it is read directly).
    if (m_samples > 1) {
        glBlitNamedFramebuffer(m_msFramebuffer, m_framebuffer, 0, 0, W, H, 0, 0, W, H,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    stamp(m_queries[4]);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    m_timed = m_timing;
    m_splashTimed = !splashes.empty();
    checkGl("drawing the splashes");
}

Mat4 WaterRenderer::viewProjection(const Camera& camera) const {
    const double aspect = static_cast<double>(m_shading.width) / m_shading.height;
    return multiply(projectionMatrix(camera, aspect), viewMatrix(camera));
}

double WaterRenderer::pixelsPerMetre(const Camera& camera) const {
    // Pixels per metre at unit distance: height / (2 tan(fov / 2)).
    return m_shading.height / (2.0 * std::tan(0.5 * camera.fovYDegrees * std::numbers::pi / 180.0));
}

MeshLayout WaterRenderer::meshLayout() const {
    return {.verticesX = m_grid.cellsX,
            .verticesZ = m_grid.cellsZ,
            .x0 = m_grid.x0 + 0.5 * m_grid.dx,
            .z0 = 0.5 * m_grid.dz,
            .dx = m_grid.dx,
            .dz = m_grid.dz};
}

void WaterRenderer::updateMeshOrder(const Vec3& eye) {
    const std::vector<std::uint32_t> indices = frontToBackIndices(meshLayout(), eye);
    glNamedBufferSubData(m_indices.get(), 0,
                         static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                         indices.data());
    m_indexEye = eye;
    m_indexValid = true;
}

void WaterRenderer::renderBackground(const Camera& camera, const Mat4& invViewProj,
                                     GlName heightBuffer) {
    // The environment seen through each pixel, sky and floor; it depends on the camera only, so
    // it is drawn once per camera and copied into every frame. The block's shadow on the floor
    // is that of its mean water level in the frame drawn then.
    if (m_shading.floor.enabled) {
        std::vector<float> heights(static_cast<std::size_t>(m_grid.cellsX) * m_grid.cellsZ);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(heightBuffer, 0,
                                static_cast<GLsizeiptr>(heights.size() * sizeof(float)),
                                heights.data());
        double sum = 0.0;
        for (float h : heights)
            sum += std::max(h, m_domain.yMin);
        glProgramUniform1f(m_skyProgram.get(), kBlockTop,
                           static_cast<float>(sum / static_cast<double>(heights.size())));
    }
    glEnable(GL_FRAMEBUFFER_SRGB);
    glBindFramebuffer(GL_FRAMEBUFFER, m_backgroundFramebuffer);
    glViewport(0, 0, m_shading.width, m_shading.height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindTextureUnit(0, m_sky.get());
    glProgramUniformMatrix4fv(m_skyProgram.get(), kViewProj, 1, GL_FALSE, invViewProj.data());
    setVec3(m_skyProgram.get(), kEye, camera.position);
    glUseProgram(m_skyProgram.get());
    glBindVertexArray(m_vertexArray);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    m_backgroundCamera = camera;
    m_backgroundValid = true;
}

Image WaterRenderer::readPixels() const {
    const int W = m_shading.width, H = m_shading.height;
    Image image(W, H);
    std::vector<std::uint8_t> rows(static_cast<std::size_t>(W) * H * 3);
    glDisable(GL_FRAMEBUFFER_SRGB); // read the stored sRGB bytes as they are
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m_samples > 1 ? m_framebuffer : m_msFramebuffer);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, W, H, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    checkGl("reading the picture back");
    // GL's row 0 is the bottom; images have row 0 at the top.
    const std::size_t stride = static_cast<std::size_t>(W) * 3;
    for (int y = 0; y < H; ++y) {
        std::copy_n(rows.data() + static_cast<std::size_t>(H - 1 - y) * stride, stride,
                    image.pixel(0, y));
    }
    return image;
}

StageTimes WaterRenderer::stageTimes() const {
    if (!m_timed)
        throw std::logic_error("stageTimes() without a timed draw()");
    StageTimes t;
    t.skyMs = elapsedMs(m_queries[0], m_queries[1]);
    t.waterMs = elapsedMs(m_queries[1], m_queries[2]);
    t.splashMs = m_splashTimed ? elapsedMs(m_queries[2], m_queries[3]) : 0.0;
    t.resolveMs = elapsedMs(m_queries[3], m_queries[4]);
    return t;
}

} // namespace swell::runtime
