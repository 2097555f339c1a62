#version 450 core
// Sec. 5: the vertices of the water mesh, one per cell centre of the reconstructed height field
// (eq. 7; vertex m * N + n, the layout of GpuReplay::heightBuffer): position, normal by central
// differences of the neighbouring heights (one-sided at the edges), the reflected view ray, and
// the shading that varies slowly over the surface: the colour along the refracted ray, the
// reflected environment (cube map) and the Fresnel weight (Schlick), mixed. water.frag adds the
// per-pixel sun highlight around the interpolated reflected ray.
// A compute pass: llvmpipe runs it on every core, while its vertex shaders run on one thread and
// once per triangle corner, so water.vert only fetches these. It writes u_rows rows of vertices
// from row u_firstRow per dispatch, into a range of the vertex buffer bound at that row: a
// mesh whose vertex buffer exceeds the driver's largest shader-storage block is written in
// several dispatches.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Heights { float h[]; };
struct Vertex {
    vec4 position;  // xyz, metres; w = 1
    vec4 reflected; // xyz: the reflected view ray (unit; y >= 0, see below); w = 0
    vec4 shade;     // rgb: mix(refracted, reflected, F), linear; a: F
};
layout(std430, binding = 1) writeonly buffer Vertices { Vertex vertices[]; };

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
layout(location = 11) uniform float u_f0;             // Schlick's F0 = ((n - 1) / (n + 1))^2
layout(location = 18) uniform float u_reflectionLod; // fixed cube-map level of the reflections
layout(location = 25) uniform int u_firstRow;        // the row m of vertices[0]
layout(location = 26) uniform int u_rows;            // the rows this dispatch writes
layout(binding = 0) uniform samplerCube u_sky;

float heightAt(int n, int m) {
    n = clamp(n, 0, u_cells.x - 1);
    m = clamp(m, 0, u_cells.y - 1);
    return h[m * u_cells.x + n];
}

void main() {
    const int id = int(gl_GlobalInvocationID.x);
    if (id >= u_cells.x * u_rows) return;
    const int n = id % u_cells.x;
    const int m = u_firstRow + id / u_cells.x;
    const float y = heightAt(n, m);
    const int n0 = max(n - 1, 0), n1 = min(n + 1, u_cells.x - 1);
    const int m0 = max(m - 1, 0), m1 = min(m + 1, u_cells.y - 1);
    const float dhdx =
        (heightAt(n1, m) - heightAt(n0, m)) / (float(max(n1 - n0, 1)) * u_spacing.x);
    const float dhdz =
        (heightAt(n, m1) - heightAt(n, m0)) / (float(max(m1 - m0, 1)) * u_spacing.y);
    const vec3 normal = normalize(vec3(-dhdx, 1.0, -dhdz));
    const vec3 world =
        vec3(u_origin.x + float(n) * u_spacing.x, y, u_origin.y + float(m) * u_spacing.y);

    // Refraction: the ray goes down to the bed; light is absorbed along the path (Beer-Lambert)
    // and scattered in, so deep water tends to u_scatter and shallow water shows the bed, lit
    // by the sun through the water above it.
    const vec3 V = normalize(u_eye - world);
    const vec3 T = refract(-V, normal, u_eta);
    const float depth = max(y - u_bedY, 0.0);
    const float path = T.y < -1e-3 ? depth / -T.y : 20.0 * depth + 1.0;
    const vec3 transmit = exp(-u_absorption * path);
    const float sunDown = max(u_sunDir.y, 0.15);
    const vec3 bedLit = u_bed * (0.25 + 0.75 * sunDown) * exp(-u_absorption * depth / sunDown);

    const vec3 refracted = bedLit * transmit + u_scatter * (1.0 - transmit);

    // Reflection of the environment; a normal facing away from the eye (a silhouette) is
    // turned towards it. A reflected ray into the water would hit the surface again: take the sky.
    vec3 N = normal;
    if (dot(N, V) < 0.0) N = normalize(N - 1.01 * dot(N, V) * V);
    vec3 R = reflect(-V, N);
    R.y = abs(R.y);
    const vec3 reflected = textureLod(u_sky, R, u_reflectionLod).rgb;
    // Fresnel, Schlick's approximation: F0 + (1 - F0) (1 - cos)^5.
    const float c = 1.0 - clamp(dot(N, V), 0.0, 1.0);
    const float c2 = c * c;
    const float F = u_f0 + (1.0 - u_f0) * (c2 * c2 * c);

    vertices[id].position = vec4(world, 1.0);
    vertices[id].reflected = vec4(R, 0.0);
    vertices[id].shade = vec4(mix(refracted, reflected, F), F);
}
