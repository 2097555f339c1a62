#version 450 core
// The four sides of the water block: a strip from the height-field edge (eq. 7 heights) down to
// the bed, so the replayed volume reads as a tank of water rather than a floating sheet.
// A side is a flat glass wall: its faint sky reflection and Fresnel weight vary slowly along it
// and are computed here, per vertex; skirt.frag only adds the absorption with depth.

layout(std430, binding = 0) readonly buffer Heights { float h[]; };

layout(location = 0) uniform mat4 u_viewProj;
layout(location = 1) uniform ivec2 u_cells;  // N, M
layout(location = 2) uniform vec2 u_origin;  // x, z of the centre of cell (0, 0)
layout(location = 3) uniform vec2 u_spacing; // dx, dz
layout(location = 4) uniform vec3 u_eye;
layout(location = 6) uniform float u_bedY;
layout(location = 11) uniform float u_f0;    // Schlick's F0
layout(location = 14) uniform int u_edge;    // 0: m = 0, 1: m = M - 1, 2: n = 0, 3: n = N - 1
layout(binding = 0) uniform samplerCube u_sky;

out float v_below;      // depth below the local surface, metres
out vec4 v_reflection;  // rgb: F x reflected sky (linear), a: F

void main() {
    const int i = gl_VertexID / 2;
    const bool top = (gl_VertexID % 2) == 0;
    int n, m;
    vec3 normal;
    if (u_edge < 2) {
        n = i;
        m = u_edge == 0 ? 0 : u_cells.y - 1;
        normal = vec3(0.0, 0.0, u_edge == 0 ? -1.0 : 1.0);
    } else {
        m = i;
        n = u_edge == 2 ? 0 : u_cells.x - 1;
        normal = vec3(u_edge == 2 ? -1.0 : 1.0, 0.0, 0.0);
    }
    const float surface = h[m * u_cells.x + n];
    const float y = top ? surface : u_bedY;
    // Linear along the strip's triangles, as (surface - y) is: exact when interpolated.
    v_below = surface - y;
    const vec3 world =
        vec3(u_origin.x + float(n) * u_spacing.x, y, u_origin.y + float(m) * u_spacing.y);
    const vec3 V = normalize(u_eye - world);
    const float c = 1.0 - clamp(abs(dot(normal, V)), 0.0, 1.0);
    const float c2 = c * c;
    const float F = u_f0 + (1.0 - u_f0) * (c2 * c2 * c); // Schlick
    v_reflection = vec4(F * textureLod(u_sky, reflect(-V, normal), 0.0).rgb, F);
    gl_Position = u_viewProj * vec4(world, 1.0);
}
