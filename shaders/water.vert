#version 450 core
// Sec. 5: the reconstructed height field (eq. 7) drawn as a mesh, one vertex per cell centre
// (vertex id = m * N + n, the layout of GpuReplay::heightBuffer). Normals by central
// differences of the neighbouring heights (one-sided at the edges).

layout(std430, binding = 0) readonly buffer Heights { float h[]; };

layout(location = 0) uniform mat4 u_viewProj;
layout(location = 1) uniform ivec2 u_cells;  // N, M
layout(location = 2) uniform vec2 u_origin;  // x, z of the centre of cell (0, 0), metres
layout(location = 3) uniform vec2 u_spacing; // dx, dz, metres

out vec3 v_world;
out vec3 v_normal;

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
    const float dhdx = (heightAt(n1, m) - heightAt(n0, m)) / (float(max(n1 - n0, 1)) * u_spacing.x);
    const float dhdz = (heightAt(n, m1) - heightAt(n, m0)) / (float(max(m1 - m0, 1)) * u_spacing.y);
    v_normal = normalize(vec3(-dhdx, 1.0, -dhdz));
    v_world = vec3(u_origin.x + float(n) * u_spacing.x, y, u_origin.y + float(m) * u_spacing.y);
    gl_Position = u_viewProj * vec4(v_world, 1.0);
}
