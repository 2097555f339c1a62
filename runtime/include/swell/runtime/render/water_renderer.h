#pragma once
// Shaded water (Sec. 5): draws a height field (GpuReplay::heightBuffer, or any mode's buffer
// of the same layout) as a mesh with cube-map reflection, refraction and Fresnel, the block's
// sides, and splash point sprites, into an offscreen (optionally multisampled) framebuffer,
// and reads the picture back. Needs a current GL context (EglContext). The renderer does not
// know where the heights come from: a replay mode only changes who writes the buffer.

#include "swell/cache/header.h"
#include "swell/runtime/gl/gl_objects.h"
#include "swell/runtime/io/image_io.h"
#include "swell/runtime/render/camera.h"
#include "swell/runtime/render/mesh_order.h"
#include "swell/runtime/render/sky_cubemap.h"
#include "swell/runtime/render/splash_system.h"
#include "swell/runtime/replay/replay_params.h"
#include "swell/runtime/stage_times.h"

#include <span>
#include <vector>

namespace swell::runtime {

/// The floor the water block stands on (shaders/sky.frag): an endless plane of square stone
/// tiles at the bed height (domain yMin) with the bed's colour (ShadingParams::bedColour), lit
/// by the sun and the sky like the bed seen through the water, shadowed by the block, fading
/// into the horizon with distance. Drawn with the sky, once per camera.
struct FloorParams {
    bool enabled = true;        ///< draw the floor (false: the sky's ground below the horizon)
    double tileSize = 0.25;     ///< edge of a tile, metres (> 0)
    double tileContrast = 0.18; ///< brightness spread between tiles, 0..1
    double hazeDistance = 30.0; ///< distance over which the floor fades into the horizon, m
    /// Throws std::invalid_argument naming the field.
    void validate() const;
};

struct ShadingParams {
    int width = 1280; ///< image width, pixels
    int height = 720; ///< image height, pixels
    int samples = 1; ///< multisampling (1: off; its cost: docs/BENCHMARKS.md); capped by the driver
    double refractiveIndex = 1.333; ///< water; Schlick's F0 = ((n - 1) / (n + 1))^2
    /// Beer-Lambert coefficients along the refracted ray, per metre (R, G, B).
    Vec3 absorption{2.2, 0.75, 0.55};
    Vec3 scatterColour{0.015, 0.11, 0.15}; ///< colour deep water tends to, linear RGB
    Vec3 bedColour{0.62, 0.55, 0.40}; ///< bed (sand) albedo seen through shallow water, linear RGB
    double sunShininess = 900.0;      ///< exponent of the sun highlight lobe
    double sunIntensity = 8.0;        ///< strength of the sun highlight
    Vec3 sunColour{1.0, 0.95, 0.85};  ///< sun highlight colour, linear RGB
    Vec3 splashColour{0.92, 0.95, 1.0}; ///< splash droplets, linear RGB
    bool sides = true;                  ///< draw the block's four sides down to the bed
    /// Cube-map mip level of the reflections (fixed: no derivatives, fast on llvmpipe).
    double reflectionLod = 1.0;
    FloorParams floor; ///< the floor around and under the block
    /// Most mesh rows the vertex pass writes per dispatch (0: as many as one shader-storage
    /// block of the driver holds); a mesh beyond one block is written in several.
    int vertexRowsPerDispatch = 0;

    /// Throws std::invalid_argument naming the field.
    void validate() const;
};

class WaterRenderer {
public:
    /// Throws std::invalid_argument naming cells_x x cells_z and what fits when the current GL
    /// context cannot hold a mesh of cellsX x cellsZ cells (its height buffer, 4 bytes a cell,
    /// is bound whole as one shader-storage block). Needs a current context.
    static void checkMeshFits(int cellsX, int cellsZ);

    /// `grid` and `domain` place the mesh (bed at domain.yMin); `sky` is the environment
    /// (proceduralSky or loadSkyImages), `sun` the direction of the highlight. Throws
    /// std::invalid_argument (parameters, a mesh beyond checkMeshFits) or RuntimeError (GL:
    /// shaders, framebuffer).
    WaterRenderer(const Grid& grid, const cache::Domain& domain, const ShadingParams& shading,
                  const CubeFaces& sky, const Vec3& sun);
    ~WaterRenderer();
    WaterRenderer(const WaterRenderer&) = delete;
    WaterRenderer& operator=(const WaterRenderer&) = delete;

    /// Draws one frame: sky (rendered once per camera, then copied), the height field in
    /// `heightBuffer` (an SSBO of N x M floats, [m * N + n], metres), the sides and, if `splashes`
    /// is not empty, the splash sprites of radius `splashRadius` metres. Returns without waiting
    /// for the GPU. The same as drawSurface then drawSplashes.
    void draw(GlName heightBuffer, const Camera& camera, std::span<const SplashSprite> splashes,
              double splashRadius);
    /// The first part of draw(): sky, height field and sides, handed to the GPU (flushed) so
    /// that the caller can build the splash sprites while they are drawn. `splashesFollow`: the
    /// heights are read back for culling the drops under the surface (drawSplashes).
    void drawSurface(GlName heightBuffer, const Camera& camera, bool splashesFollow);
    /// The second part: the splash sprites over the surface of the last drawSurface (none: no
    /// splash pass), and the resolve. Throws std::logic_error without a drawSurface first, or
    /// with sprites after drawSurface(..., splashesFollow = false).
    void drawSplashes(std::span<const SplashSprite> splashes, double splashRadius);
    /// Resolves and reads the last frame back (blocks): 8-bit RGB, row 0 at the top.
    Image readPixels() const;
    /// Puts GL timestamp queries around each stage of draw(), each after a glFinish (so a timed
    /// frame is serialised stage by stage and a little slower).
    void setTiming(bool on) { m_timing = on; }
    /// Stage times of the last timed draw(); waits for the GPU.
    /// Sky, water, splashes and resolve of the last timed draw (GL timestamp queries).
    StageTimes stageTimes() const;
    /// The multisample count in use (after the driver's cap).
    int samples() const { return m_samples; }
    /// Splash sprites drawn by the last draw() (0: no splash pass ran).
    std::size_t lastSplashCount() const { return m_lastSplashes; }
    /// Of those, the sprites not drawn because they were under the water (cullSubmergedSplashes).
    std::size_t lastCulledSplashCount() const { return m_lastCulled; }

private:
    /// The mesh's index and vertex buffers, the splash buffer and their vertex arrays.
    void createMeshBuffers();
    /// Runs surface_vertices.comp over the mesh, m_rowsPerDispatch rows at a time.
    void writeVertices();
    /// The offscreen framebuffers (multisampled, resolved, background); throws RuntimeError
    /// when one is incomplete.
    void createFramebuffers();
    /// Uniforms of the surface, the sides and the floor that do not change between frames.
    void setSurfaceUniforms();
    /// Sun, side and splash lighting uniforms; the ambient light is the zenith radiance of `sky`.
    void setLightUniforms(const CubeFaces& sky);
    void renderBackground(const Camera& camera, const Mat4& invViewProj, GlName heightBuffer);
    void updateMeshOrder(const Vec3& eye);
    void stamp(const GlQuery& query) const;
    MeshLayout meshLayout() const;
    Mat4 viewProjection(const Camera& camera) const;
    double pixelsPerMetre(const Camera& camera) const;

    Grid m_grid;
    cache::Domain m_domain;
    ShadingParams m_shading;
    Vec3 m_sun;
    int m_samples = 1;
    bool m_timing = false;
    bool m_timed = false;
    bool m_splashTimed = false;
    std::size_t m_lastSplashes = 0;
    std::size_t m_splashCapacity = 0;
    std::size_t m_lastCulled = 0;
    std::vector<float> m_heights;               // read back for the splash culling
    bool m_heightsValid = false;                // m_heights are this frame's
    bool m_surfaceDrawn = false;                // drawSurface ran, drawSplashes has not
    Camera m_frameCamera;                       // the last drawSurface's, for drawSplashes
    std::vector<SplashSprite> m_visibleSprites; // the sprites drawn

    GlProgram m_skyProgram;
    GlProgram m_waterProgram;
    GlProgram m_surfaceProgram; // surface_vertices.comp
    GlBuffer m_vertices;        // its output, the mesh's vertex buffer
    GlProgram m_skirtProgram;
    GlProgram m_splashProgram;
    GlProgram m_backgroundProgram;
    GlTexture m_background; // the sky pass for m_backgroundCamera
    GlName m_backgroundFramebuffer = 0;
    Camera m_backgroundCamera;
    bool m_backgroundValid = false;
    GlTexture m_sky;
    GlBuffer m_indices; // the mesh's triangles, front to back from m_indexEye
    Vec3 m_indexEye{0.0, 0.0, 0.0};
    bool m_indexValid = false;
    GlBuffer m_splashBuffer;
    GlName m_vertexArray = 0; // no attributes
    GlName m_meshArray = 0;   // the mesh: m_vertices + m_indices
    GlName m_splashArray = 0;
    GlName m_msFramebuffer = 0;
    GlName m_framebuffer = 0;
    GlName m_renderbuffers[3] = {0, 0, 0}; // multisampled colour, depth; resolved colour
    GlQuery m_queries[5];
    std::size_t m_indexCount = 0;
    int m_rowsPerDispatch = 1; // mesh rows surface_vertices.comp writes per dispatch
};

} // namespace swell::runtime
