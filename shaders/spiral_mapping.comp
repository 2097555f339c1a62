#version 450 core
// Whirlpool (Sec. 4.5): the J = 2K - 1 slices, sampled by eq. (5)-(6) (slice_lookup.comp),
// are bent into log spirals r(t) = a e^(b t) at angle phi_j + t, t in [0, 2 pi], with
// phi_j = 2 pi j / J + spin(tau). A cell at polar (r, theta) about the centre lies at spiral
// parameter t = ln(r / a) / b (clamped to [0, 2 pi]) and slice coordinate
// s = (theta - t - spin) J / (2 pi) mod J; the cache's x runs along the spiral, column
// coordinate u = N t / (2 pi). Its height is the box mean over the cell's footprint
// (whirlpool.h): across the spirals, w slices of the spirals interpolated linearly in s
// (spiral j weighs [H(s + w/2 - j) - H(s - w/2 - j)] / w, H the integral of the hat
// max(0, 1 - |x|)); along them, wu columns of each spiral's eq. (7) column profile (linear
// between column centres; column_pass.comp's S / W, or the fallback when W = 0), from the
// profile's integral stored per held frame and column centre k as (p(k), p(min(k + 1, N - 1)),
// C(k) as a float and the float of its remainder, so that differences of C keep float
// precision). Each spiral blends its frame with the second stored frame of slice_lookup.comp's
// binding 4 (TimeSampling::Linear). Minus the eye funnel's depth. Per cell the geometry
// (v = u - 1/2, wu, s at spin 0, w, funnel) is precomputed on the CPU in double.
layout(local_size_x = 64) in;

struct Cell {
    float v;   // profile coordinate u - 1/2 (column centres at integers)
    float wu;  // footprint width along the profile, columns, >= 1
    float s;   // slice coordinate at spin 0, in [0, J)
    float w;   // footprint width across the spirals, slices, in [1, J]
    float dip; // eye funnel depth, metres
    float pad0;
    float pad1;
    float pad2;
};

layout(std430, binding = 0) readonly buffer Slices { ivec2 slices[]; };   // (frame, slot) per j
layout(std430, binding = 1) readonly buffer Profiles { vec4 profiles[]; }; // slot * N + k
layout(std430, binding = 2) readonly buffer Cells { Cell cells[]; };     // m * N + n
layout(std430, binding = 3) writeonly buffer Heights { float heights[]; }; // m * N + n
layout(std430, binding = 4) readonly buffer Blend { vec2 blend[]; };     // (second slot, weight)

uniform int u_cells;       // N * M
uniform int u_N;           // columns of the profile
uniform int u_J;           // slices, 2K - 1
uniform float u_spin;      // spin(tau) in slice units, in [0, J)
uniform float u_reference; // level added back (columns are relative)
uniform float u_missing;   // relative height of a slice whose frame is not held

// The integral of slot's profile from v = 0 to v, as (float part of C, the rest).
vec2 integral(int slot, float v) {
    if (v <= 0.0) return vec2(0.0, v * profiles[slot * u_N].x);
    float last = float(u_N - 1);
    if (v >= last) {
        vec4 q = profiles[slot * u_N + u_N - 1];
        return vec2(q.z, q.w + (v - last) * q.x);
    }
    int k = int(floor(v));
    float a = v - float(k);
    vec4 q = profiles[slot * u_N + k];
    return vec2(q.z, q.w + a * q.x + 0.5 * a * a * (q.y - q.x));
}

// The box mean of slot's profile over [v0, v1] (relative height).
float boxMean(int slot, float v0, float v1) {
    if (slot < 0) return u_missing;
    vec2 a = integral(slot, v0);
    vec2 b = integral(slot, v1);
    return ((b.x - a.x) + (b.y - a.y)) / (v1 - v0);
}

// Slice j's profile box mean over [v0, v1], blended in time.
float spiral(int j, float v0, float v1) {
    float h = boxMean(slices[j].y, v0, v1);
    vec2 b = blend[j];
    if (b.y > 0.0) h = mix(h, boxMean(int(b.x), v0, v1), b.y);
    return h;
}

float hatIntegral(float x) {
    if (x <= -1.0) return 0.0;
    if (x <= 0.0) return 0.5 * (x + 1.0) * (x + 1.0);
    if (x < 1.0) return 1.0 - 0.5 * (1.0 - x) * (1.0 - x);
    return 1.0;
}

void main() {
    int c = int(gl_GlobalInvocationID.x);
    if (c >= u_cells) return;
    Cell cell = cells[c];
    float s = cell.s - u_spin;
    if (s < 0.0) s += float(u_J);
    float half_w = 0.5 * cell.w;
    float v0 = cell.v - 0.5 * cell.wu;
    float v1 = cell.v + 0.5 * cell.wu;
    int first = int(floor(s - half_w)) - 1;
    int last = int(floor(s + half_w)) + 1;
    float h = 0.0;
    for (int j = first; j <= last; ++j) {
        float x = float(j) - s;
        float k = (hatIntegral(half_w - x) - hatIntegral(-half_w - x)) / cell.w;
        if (k == 0.0) continue;
        int jw = (j + 2 * u_J) % u_J; // j >= -J - 2: % of a negative int is undefined
        h += k * spiral(jw, v0, v1);
    }
    heights[c] = h + u_reference - cell.dip;
}
