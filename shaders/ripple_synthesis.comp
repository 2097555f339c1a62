#version 450 core
// Ripple synthesis, eq. (8) of the paper (Sec. 4.4): the height of base-mesh cell c is the
// weighted sum over the directions d of the bilinearly interpolated heights of the 2 x 2 cell
// centres Q around the cell's position in direction d's rotated grid:
//     h(P) = sum_d w_d bilerp(h_d; Q00, Q10, Q01, Q11; fx, fz)
// The taps (neighbour index, fractions, weight) are fixed by the geometry and computed once
// on the CPU in double precision (runtime/src/ripple_synthesis.cpp, rippleTaps): x clamped to
// the direction's edge columns, z periodic (row M - 1 neighbours row 0).
layout(local_size_x = 64) in;

struct Tap {
    int base;    // d * N * M + m0 * N + n0
    int rowStep; // (m1 - m0) * N
    float fx;  // bilinear fraction along the direction's x
    float fz;  // bilinear fraction along the direction's z
    float w;   // eq. (8) weight
};

layout(std430, binding = 0) readonly buffer Directions { float dirHeights[]; }; // D x N x M
layout(std430, binding = 1) readonly buffer Taps { Tap taps[]; };               // c * D + d
layout(std430, binding = 2) writeonly buffer Heights { float heights[]; };      // m * N + n

uniform int u_cells; // N * M
uniform int u_D;     // directions
uniform int u_stepX; // n1 - n0: 1, or 0 when N = 1

void main() {
    int c = int(gl_GlobalInvocationID.x);
    if (c >= u_cells) return;
    float h = 0.0;
    for (int d = 0; d < u_D; ++d) {
        Tap t = taps[c * u_D + d];
        float h00 = dirHeights[t.base];
        float h10 = dirHeights[t.base + u_stepX];
        float h01 = dirHeights[t.base + t.rowStep];
        float h11 = dirHeights[t.base + t.rowStep + u_stepX];
        h += t.w * mix(mix(h00, h10, t.fx), mix(h01, h11, t.fx), t.fz); // eq. (8)
    }
    heights[c] = h;
}
