#version 450 core
// The four sides of the water block: a strip from the height-field edge (eq. 7 heights) down to
// the bed, so the replayed volume reads as a tank of water rather than a floating sheet.

layout(std430, binding = 0) readonly buffer Heights { float h[]; };

layout(location = 0) uniform mat4 u_viewProj;
layout(location = 1) uniform ivec2 u_cells;  // N, M
layout(location = 2) uniform vec2 u_origin;  // x, z of the centre of cell (0, 0)
layout(location = 3) uniform vec2 u_spacing; // dx, dz
layout(location = 6) uniform float u_bedY;
layout(location = 14) uniform int u_edge;    // 0: m = 0, 1: m = M - 1, 2: n = 0, 3: n = N - 1

out vec3 v_world;
out float v_surface;
flat out vec3 v_normal;

void main() {
    const int i = gl_VertexID / 2;
    const bool top = (gl_VertexID % 2) == 0;
    int n, m;
    if (u_edge < 2) {
        n = i;
        m = u_edge == 0 ? 0 : u_cells.y - 1;
        v_normal = vec3(0.0, 0.0, u_edge == 0 ? -1.0 : 1.0);
    } else {
        m = i;
        n = u_edge == 2 ? 0 : u_cells.x - 1;
        v_normal = vec3(u_edge == 2 ? -1.0 : 1.0, 0.0, 0.0);
    }
    v_surface = h[m * u_cells.x + n];
    const float y = top ? v_surface : u_bedY;
    v_world = vec3(u_origin.x + float(n) * u_spacing.x, y, u_origin.y + float(m) * u_spacing.y);
    gl_Position = u_viewProj * vec4(v_world, 1.0);
}
