#version 450 core
// Whirlpool (Sec. 4.5): the J = 2K - 1 slices, sampled by eq. (5)-(6) (slice_lookup.comp),
// are bent into log spirals r(t) = a e^(b t) at angle phi_j + t, t in [0, 2 pi], with
// phi_j = 2 pi j / J + spin(tau). A cell at polar (r, theta) about the centre lies at spiral
// parameter t = ln(r / a) / b (clamped to [0, 2 pi]) and slice coordinate
// s = (theta - t - spin) J / (2 pi) mod J; the cache's x runs along the spiral, column
// coordinate u = N t / (2 pi). Its height interpolates the two nearest spirals j0 = floor(s),
// j1 = j0 + 1 mod J (weight s - j0), each read at u from the frame's eq. (7) column profile
// (column_pass.comp: S / W, or the fallback when W = 0; stored once per held frame as pairs
// (p(n), p(min(n + 1, N - 1))) so one load serves the interpolation) linearly between column
// centres. Per cell the geometry (n0, beta, s at spin 0) is precomputed on the CPU in double.
layout(local_size_x = 64) in;

struct Cell {
    int n0;     // lower column of the profile interpolation
    float beta; // weight of column min(n0 + 1, N - 1)
    float s;    // slice coordinate at spin 0, in [0, J)
    float pad;
};

layout(std430, binding = 0) readonly buffer Slices { ivec2 slices[]; };   // (frame, slot) per j
layout(std430, binding = 1) readonly buffer Profiles { vec2 profiles[]; }; // slot * N + n
layout(std430, binding = 2) readonly buffer Cells { Cell cells[]; };     // m * N + n
layout(std430, binding = 3) writeonly buffer Heights { float heights[]; }; // m * N + n

uniform int u_cells;       // N * M
uniform int u_N;           // columns of the profile
uniform int u_J;           // slices, 2K - 1
uniform float u_spin;      // spin(tau) in slice units, in [0, J)
uniform float u_reference; // level added back (columns are relative)
uniform float u_missing;   // relative height of a slice whose frame is not held

// The eq. (7) profile of slice j's frame at u (relative height).
float spiral(int j, int n0, float beta) {
    int slot = slices[j].y;
    if (slot < 0) return u_missing;
    vec2 p = profiles[slot * u_N + n0];
    return mix(p.x, p.y, beta);
}

void main() {
    int c = int(gl_GlobalInvocationID.x);
    if (c >= u_cells) return;
    Cell cell = cells[c];
    float s = cell.s - u_spin;
    if (s < 0.0) s += float(u_J);
    int j0 = int(floor(s));
    float alpha = s - float(j0);
    if (j0 >= u_J) { j0 = 0; alpha = 0.0; } // rounding at the wrap
    int j1 = j0 + 1 == u_J ? 0 : j0 + 1;
    float h = mix(spiral(j0, cell.n0, cell.beta), spiral(j1, cell.n0, cell.beta), alpha);
    heights[c] = h + u_reference;
}
