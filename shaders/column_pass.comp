#version 450 core
// The x half of the separable eq. (7) Gaussian, once per resident cache frame and column n:
//     S = sum_p G_x(p) h_p,  W = sum_p G_x(p),  G_x = exp(-(u_p - (n + 1/2))^2 / (2 sigma^2))
// over the frame's surface particles whose x bin (floor of u_p, u in cells) is n - 1, n or
// n + 1: the [3 dx) part of the cut-off window. Heights are relative to a reference level.
// Each column stores (h, W) with h = S / W, the column's height, so that reconstruct.comp blends
// two frames' columns without a division. A column with no particle in its window stores
// (fallback, 0): the mean height of the
// particles in the nearest non-empty bins at distance d >= 2 (both sides when tied), or the
// empty-frame height when the frame has no surface particle.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Particles { vec2 particles[]; };  // (u, h - ref)
layout(std430, binding = 1) readonly buffer Bins { uint binStart[]; };        // per slot: N + 3
// Columns are grouped by four for reconstruct.comp: for each slot and quad q = n / 4, one vec4 of
// h = S / W (or the fallback) then one vec4 of W; a float index ((slot * Nq + q) * 2 + c) * 4 + n % 4.
layout(std430, binding = 2) writeonly buffer Columns { float columns[]; };

uniform int u_N;             // columns
uniform int u_Nq;            // column quads, ceil(N / 4)
uniform int u_slots;         // resident frames
uniform int u_slotBase;      // slot of work-group row 0 (dispatches run in batches of rows)
uniform float u_sigma;       // Gaussian sigma in cells
uniform float u_emptyHeight; // height (relative) of a frame with no surface particle

// Bins run from -1 to N (particles a cell beyond either end still reach the edge columns).
uint binBegin(int slot, int b) { return binStart[slot * (u_N + 3) + b + 1]; }

// Adds the heights and the number of the particles in bin b (ignored outside -1 .. N).
void addBin(int slot, int b, inout float sum, inout uint count) {
    if (b < -1 || b > u_N) return;
    uint first = binBegin(slot, b);
    uint last = binBegin(slot, b + 1);
    for (uint p = first; p < last; ++p) sum += particles[p].y;
    count += last - first;
}

void main() {
    int n = int(gl_GlobalInvocationID.x);
    int slot = u_slotBase + int(gl_GlobalInvocationID.y);
    if (n >= u_N || slot >= u_slots) return;

    float centre = float(n) + 0.5;
    float inv2s2 = 1.0 / (2.0 * u_sigma * u_sigma);
    float S = 0.0;
    float W = 0.0;
    uint first = binBegin(slot, n - 1);
    uint last = binBegin(slot, n + 2);
    for (uint p = first; p < last; ++p) {
        vec2 q = particles[p];
        float d = q.x - centre;
        float g = exp(-d * d * inv2s2);                       // eq. (7): x factor of G
        S += g * q.y;
        W += g;
    }
    int base = ((slot * u_Nq + n / 4) * 2) * 4 + n % 4;
    if (W > 0.0) {
        columns[base] = S / W;
        columns[base + 4] = W;
        return;
    }
    // Fallback: nearest non-empty bins at distance d >= 2.
    float fallback = u_emptyHeight;
    for (int d = 2; n - d >= -1 || n + d <= u_N; ++d) {
        float sum = 0.0;
        uint count = 0u;
        addBin(slot, n - d, sum, count);
        addBin(slot, n + d, sum, count);
        if (count > 0u) {
            fallback = sum / float(count);
            break;
        }
    }
    columns[base] = fallback;
    columns[base + 4] = 0.0;
}
