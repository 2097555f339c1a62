#version 450 core
// Height of every base-mesh cell, eq. (7) of the paper, from the per-frame column sums
// (column_pass.comp) of the slices in the cell's z window [-dz, dz) (Sec. 4.2):
//     h = sum_j G_z(j) S[s_j][n] / sum_j G_z(j) W[s_j][n]
// which is the Gaussian-weighted mean of every surface particle in the [3 dx, 2 dz) window
// because G = G_x G_z. When no slice contributes a particle (W = 0), the height is the
// G_z-weighted mean of the slices' column fallbacks, so no cell is a hole or NaN.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Slices { ivec2 slices[]; };       // (frame, slot)
layout(std430, binding = 1) readonly buffer Columns { vec2 columns[]; };      // slot * N + n
layout(std430, binding = 2) readonly buffer Rows { ivec2 rows[]; };           // (first j, count)
layout(std430, binding = 3) readonly buffer RowWeights { float weights[]; };  // G_z per (m, i)
layout(r32f, binding = 0) writeonly uniform image2D u_height;

uniform int u_N;             // cells along x
uniform int u_M;             // cells along z
uniform int u_rowStride;     // weights per row
uniform float u_reference;   // reference level added back (heights are stored relative)
uniform float u_missing;     // relative height used for a slice whose frame is not resident

void main() {
    int n = int(gl_GlobalInvocationID.x);
    int m = int(gl_GlobalInvocationID.y);
    if (n >= u_N || m >= u_M) return;

    ivec2 row = rows[m];
    float S = 0.0;
    float W = 0.0;
    float F = 0.0;
    float G = 0.0;
    for (int i = 0; i < row.y; ++i) {
        float gz = weights[m * u_rowStride + i];             // eq. (7): z factor of G
        int slot = slices[row.x + i].y;
        vec2 c = slot >= 0 ? columns[slot * u_N + n] : vec2(u_missing, 0.0);
        if (c.y > 0.0) {
            S += gz * c.x;
            W += gz * c.y;
        } else {
            F += gz * c.x;
        }
        G += gz;
    }
    float h = W > 0.0 ? S / W : F / G;
    imageStore(u_height, ivec2(n, m), vec4(h + u_reference, 0.0, 0.0, 0.0));
}
