#version 450 core
// Sec. 5: the reconstructed height field (eq. 7) drawn as a mesh, one vertex per cell centre
// (vertex id = m * N + n, the layout of GpuReplay::heightBuffer). Normals by central
// differences of the neighbouring heights (one-sided at the edges). The refracted colour is
// computed here, per vertex: it varies slowly over the surface, and moving it out of the
// fragment shader halves the cost of a pixel on llvmpipe (reflection, Fresnel and the sun
// stay per pixel, in water.frag).

layout(std430, binding = 0) readonly buffer Heights { float h[]; };

layout(location = 0) uniform mat4 u_viewProj;
layout(location = 1) uniform ivec2 u_cells;  // N, M
layout(location = 2) uniform vec2 u_origin;  // x, z of the centre of cell (0, 0), metres
layout(location = 3) uniform vec2 u_spacing; // dx, dz, metres
layout(location = 4) uniform vec3 u_eye;
layout(location = 5) uniform vec3 u_sunDir;     // unit vector towards the sun
layout(location = 6) uniform float u_bedY;      // bed height (domain yMin), metres
layout(location = 7) uniform vec3 u_absorption; // per metre, per channel
layout(location = 8) uniform vec3 u_scatter;    // colour of light scattered by deep water
layout(location = 9) uniform vec3 u_bed;        // bed albedo
layout(location = 10) uniform float u_eta;      // n_air / n_water

out vec3 v_world;
out vec3 v_normal;
out vec3 v_refracted;

float heightAt(int n, int m) {
    n = clamp(n, 0, u_cells.x - 1);
    m = clamp(m, 0, u_cells.y - 1);
    return h[m * u_cells.x + n];
}

void main() {
    const int n = gl_VertexID % u_cells.x;
    const int m = gl_VertexID / u_cells.x;
    const float y = heightAt(n, m);
    const int n0 = max(n - 1, 0), n1 = min(n + 1, u_cells.x - 1);
    const int m0 = max(m - 1, 0), m1 = min(m + 1, u_cells.y - 1);
    const float dhdx =
        (heightAt(n1, m) - heightAt(n0, m)) / (float(max(n1 - n0, 1)) * u_spacing.x);
    const float dhdz =
        (heightAt(n, m1) - heightAt(n, m0)) / (float(max(m1 - m0, 1)) * u_spacing.y);
    v_normal = normalize(vec3(-dhdx, 1.0, -dhdz));
    v_world = vec3(u_origin.x + float(n) * u_spacing.x, y, u_origin.y + float(m) * u_spacing.y);

    // Refraction: the ray goes down to the bed; light is absorbed along the path (Beer-Lambert)
    // and scattered in, so deep water tends to u_scatter and shallow water shows the bed, lit
    // by the sun through the water above it.
    const vec3 V = normalize(u_eye - v_world);
    const vec3 T = refract(-V, v_normal, u_eta);
    const float depth = max(y - u_bedY, 0.0);
    const float path = T.y < -1e-3 ? depth / -T.y : 20.0 * depth + 1.0;
    const vec3 transmit = exp(-u_absorption * path);
    const float sunDown = max(u_sunDir.y, 0.15);
    const vec3 bedLit = u_bed * (0.25 + 0.75 * sunDown) * exp(-u_absorption * depth / sunDown);
    v_refracted = bedLit * transmit + u_scatter * (1.0 - transmit);

    gl_Position = u_viewProj * vec4(v_world, 1.0);
}
