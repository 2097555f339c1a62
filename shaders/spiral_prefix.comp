#version 450 core
// Whirlpool (Sec. 4.5), pass 1 of 2 per frame: the spirals' integrals, so that
// spiral_mapping.comp reads a cell's footprint box mean in O(1) whatever its width.
//
// Spiral j shows p_j(k), its eq. (7) column profile at column centre k (the held frame of
// slice_lookup.comp's binding 0, blended with the second stored frame of binding 4), and its
// integral along the profile C_j(k) (stored per held frame, whirlpool.h). Across the spirals,
// linear between neighbours and periodic in j, their integrals are the trapezoid sums
//     T_j(k) = sum_{i < j} (C_i(k) + C_{i+1}(k)) / 2,  P_j(k) = sum_{i < j} (p_i(k) + p_{i+1}(k)) / 2,
// i + 1 taken mod J. Row j of the tables holds (C_j(k), p_j(k)) and (T_j(k), P_j(k)) in double
// for j = 0 .. J, row J being spiral 0 again with the sums over one whole turn. One invocation
// per column k walks the spirals in order.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Slices { ivec2 slices[]; };   // (frame, slot) per j
layout(std430, binding = 1) readonly buffer Profiles { vec4 profiles[]; }; // slot * N + k
layout(std430, binding = 4) readonly buffer Blend { vec2 blend[]; };     // (second slot, weight)
layout(std430, binding = 5) writeonly buffer Along { dvec2 along[]; };   // (C, p), j * N + k
layout(std430, binding = 6) writeonly buffer Across { dvec2 across[]; }; // (T, P), j <= J

uniform int u_N;           // columns of the profile
uniform int u_J;           // spirals, 2K - 1
uniform float u_missing;   // relative height of a slice whose frame is not held

// (C, p) of slot at column k: the profile integral (float plus its remainder) and the profile.
dvec2 slotColumn(int slot, int k) {
    if (slot < 0) return dvec2(double(k) * double(u_missing), double(u_missing));
    vec4 q = profiles[slot * u_N + k];
    return dvec2(double(q.z) + double(q.w), double(q.x));
}

// (C_j(k), p_j(k)) of spiral j (taken mod J), blended in time.
dvec2 spiralColumn(int j, int k) {
    if (j >= u_J) j -= u_J;
    dvec2 c = slotColumn(slices[j].y, k);
    vec2 b = blend[j];
    if (b.y > 0.0) c = mix(c, slotColumn(int(b.x), k), double(b.y));
    return c;
}

void main() {
    int k = int(gl_GlobalInvocationID.x);
    if (k >= u_N) return;
    dvec2 prefix = dvec2(0.0);
    dvec2 here = spiralColumn(0, k);
    for (int j = 0; j < u_J; ++j) {
        dvec2 next = spiralColumn(j + 1, k);
        along[j * u_N + k] = here;
        across[j * u_N + k] = prefix;
        prefix += 0.5 * (here + next);
        here = next;
    }
    along[u_J * u_N + k] = here;
    across[u_J * u_N + k] = prefix;
}
