#version 450 core
// Height of every base-mesh cell, eq. (7) of the paper, from the per-frame column sums
// (column_pass.comp) of the slices in the cell's z window [-dz, dz) (Sec. 4.2):
//     h = sum_j G_z(j) S[s_j][n] / sum_j G_z(j) W[s_j][n]
// which is the Gaussian-weighted mean of every surface particle in the [3 dx, 2 dz) window
// because G = G_x G_z. When no slice contributes a particle (W = 0), the height is the
// G_z-weighted mean of the slices' column fallbacks, so no cell is a hole or NaN.
// One work group per row segment: m comes from gl_WorkGroupID only, so the row's slice list
// and weights are the same for every invocation of a group (uniform loads on llvmpipe). Each
// invocation computes four neighbouring cells n = 4q .. 4q + 3 with vec4 arithmetic. The host
// sets the group width to fit the row (llvmpipe pays per work group, and per idle lane).
#ifndef SWELL_QUADS_PER_GROUP
#define SWELL_QUADS_PER_GROUP 32
#endif
layout(local_size_x = SWELL_QUADS_PER_GROUP, local_size_y = 1) in;

layout(std430, binding = 0) readonly buffer Slices { ivec2 slices[]; };       // (frame, slot)
layout(std430, binding = 1) readonly buffer Columns { vec4 columns[]; };      // see column_pass
layout(std430, binding = 2) readonly buffer Rows { ivec2 rows[]; };           // (first j, count)
layout(std430, binding = 3) readonly buffer RowWeights { float weights[]; };  // G_z per (m, i)
layout(std430, binding = 4) writeonly buffer Heights { float heights[]; };    // m * N + n
layout(std430, binding = 5) readonly buffer Blend { vec2 blend[]; };          // (slot, weight)

uniform int u_N;             // cells along x
uniform int u_Nq;            // column quads, ceil(N / 4)
uniform int u_M;             // cells along z
uniform int u_rowStride;     // weights per row
uniform float u_reference;   // reference level added back (heights are stored relative)
uniform float u_missing;     // relative height used for a slice whose frame is not resident

void main() {
    int q = int(gl_GlobalInvocationID.x);
    int m = int(gl_WorkGroupID.y);
    if (q >= u_Nq || m >= u_M) return;

    ivec2 row = rows[m];
    vec4 S = vec4(0.0);
    vec4 W = vec4(0.0);
    vec4 F = vec4(0.0);
    float G = 0.0;
    for (int i = 0; i < row.y; ++i) {
        float gz = weights[m * u_rowStride + i];             // eq. (7): z factor of G
        int slot = slices[row.x + i].y;
        vec4 ch = vec4(u_missing);                           // column heights S / W (or fallback)
        vec4 cw = vec4(0.0);
        if (slot >= 0) {
            ch = columns[(slot * u_Nq + q) * 2];
            cw = columns[(slot * u_Nq + q) * 2 + 1];
        }
        vec2 b = blend[row.x + i];
        if (b.y > 0.0) {
            // Between two stored frames: blendColumns (cpu_reconstruction.cpp) of the two
            // profiles, h = mix(h_a, h_b, w), W = mix(W_a, W_b, w).
            int slot2 = int(b.x);
            vec4 ch2 = vec4(u_missing);
            vec4 cw2 = vec4(0.0);
            if (slot2 >= 0) {
                ch2 = columns[(slot2 * u_Nq + q) * 2];
                cw2 = columns[(slot2 * u_Nq + q) * 2 + 1];
            }
            ch = mix(ch, ch2, b.y);
            cw = mix(cw, cw2, b.y);
        }
        S += gz * cw * ch;                                   // sum of G h over the particles
        W += gz * cw;
        F += gz * (1.0 - vec4(greaterThan(cw, vec4(0.0)))) * ch; // fallbacks where W = 0
        G += gz;
    }
    vec4 h = mix(F / G, S / W, greaterThan(W, vec4(0.0)));
    for (int c = 0; c < 4; ++c) {
        int n = 4 * q + c;
        if (n < u_N) heights[m * u_N + n] = h[c] + u_reference;
    }
}
