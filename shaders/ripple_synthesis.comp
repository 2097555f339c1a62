#version 450 core
// Ripple synthesis, eq. (8) of the paper (Sec. 4.4): the height of base-mesh cell (n, m) is the
// weighted sum over the directions d of the bilinearly interpolated heights of the 2 x 2 cell
// centres Q around the cell's position in direction d's rotated grid:
//     h(P) = sum_d w_d bilerp(h_d; Q00, Q10, Q01, Q11; fx, fz)
// Definitions (runtime/include/swell/runtime/ripple.h): q = R(-a_d) (P - C) + C in
// the direction's cell coordinates (u, v); along x clamped to its edge columns, along z
// periodic (row M - 1 neighbours row 0); each weight tapered by e(u) near the direction's x
// ends and the weights normalised to sum 1. The position is computed here in float; the mapping
// is continuous (no coverage switch), so float rounding moves a height by ~1e-5 cells only.
// One work group per row segment (m uniform), like reconstruct.comp.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Directions { float dirHeights[]; }; // D x N x M
layout(std430, binding = 1) readonly buffer Dirs { vec4 dirs[]; }; // (cos a, sin a, w, 0)

uniform int u_N;      // cells along x
uniform int u_M;      // cells along z
uniform int u_D;      // directions
uniform float u_cx;   // C_x - x0 in cells of dx: N / 2
uniform float u_cz;   // C_z in cells of dz: M / 2
uniform float u_dzdx; // dz / dx (rotation is in metres)
uniform float u_edgeMargin; // kRippleEdgeMargin N, cells
uniform float u_edgeFloor;  // kRippleEdgeFloor

layout(std430, binding = 2) writeonly buffer Heights { float heights[]; }; // m * N + n

void main() {
    int n = int(gl_GlobalInvocationID.x);
    int m = int(gl_WorkGroupID.y);
    if (n >= u_N) return;
    // P - C in units of dx
    float px = float(n) + 0.5 - u_cx;
    float pz = (float(m) + 0.5 - u_cz) * u_dzdx;
    float h = 0.0;
    float weights = 0.0;
    float side = min(u_cx - abs(px), u_cz * u_dzdx - abs(pz)); // to the mesh's nearest side
    int cells = u_N * u_M;
    for (int d = 0; d < u_D; ++d) {
        vec4 dir = dirs[d];
        // q = R(-a_d) (P - C) + C, in the direction's cell coordinates
        float u = dir.x * px + dir.y * pz + u_cx;
        float v = (-dir.y * px + dir.x * pz) / u_dzdx + u_cz;
        float fu = clamp(u - 0.5, 0.0, float(u_N - 1));
        int n0 = max(0, min(int(floor(fu)), u_N - 2));
        int n1 = min(n0 + 1, u_N - 1);
        float fx = fu - float(n0);
        float fv = v - 0.5;
        fv -= float(u_M) * floor(fv / float(u_M));
        int m0 = min(int(floor(fv)), u_M - 1);
        float fz = fv - float(m0);
        int m1 = m0 + 1 == u_M ? 0 : m0 + 1;
        int base = d * cells;
        float h00 = dirHeights[base + m0 * u_N + n0];
        float h10 = dirHeights[base + m0 * u_N + n1];
        float h01 = dirHeights[base + m1 * u_N + n0];
        float h11 = dirHeights[base + m1 * u_N + n1];
        // eq. (8)'s weight, tapered where the direction's own field ends along x
        float a = min(u, float(u_N) - u) + max(u_edgeMargin - side, 0.0);
        float e = u_edgeFloor + (1.0 - u_edgeFloor) * smoothstep(0.0, u_edgeMargin, a);
        h += dir.z * e * mix(mix(h00, h10, fx), mix(h01, h11, fx), fz); // eq. (8)
        weights += dir.z * e;
    }
    heights[m * u_N + n] = h / weights;
}
