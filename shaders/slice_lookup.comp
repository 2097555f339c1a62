#version 450 core
// Slice lookup, eq. (5)-(6) of the paper: slice j (j = 2k is slice k, j = 2k + 1 the slice
// inserted between k and k + 1, Sec. 4.2) shows timeline entry (runtime/.../timeline.h)
//     s_j = floor((tau + F * N(tau, j / 2)) * A + 0.5)   (then clamped or wrapped)
// and, with u_linear, also the two entries around (tau + F N) A and the fraction between
// them (the time between stored frames, TimeSampling::Linear in replay_params.h).
// with N the fBm noise on the T x K grid, linear in time (period T) and, for an inserted
// slice, the mean of its two neighbours. Computed in double precision with `precise` so the
// operations match the CPU reference (runtime/src/slice_sampler.cpp) bit for bit.
layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Noise { double noise[]; };       // N[i * K + k]
layout(std430, binding = 1) readonly buffer Resident { uint slotOf[]; };     // entry -> column slot
layout(std430, binding = 2) writeonly buffer Slices { ivec2 slices[]; };     // (frame, slot) per j
layout(std430, binding = 3) readonly buffer Shown { int shownFrame[]; };     // entry -> cache frame
layout(std430, binding = 4) writeonly buffer Blend { vec2 blend[]; };        // (second slot, weight)

uniform double u_tau;        // animation time (noise time units)
uniform double u_F;          // fluctuation F, 0 <= F <= 1 (eq. 6 with max |N| = 1)
uniform double u_A;          // cache frames per animation time unit
uniform int u_T;             // noise samples in time
uniform int u_K;             // real slices
uniform int u_sliceCount;    // 2K - 1 (real + inserted)
uniform int u_frameCount;    // entries in the timeline
uniform int u_loop;          // 1: out-of-range entries wrap around; 0: clamped to the ends
uniform int u_linear;        // 1: blend the two entries around s (TimeSampling::Linear)

int wrapEntry(int s) {
    if (u_loop == 1) {
        // GLSL leaves % undefined for negative operands: keep both non-negative.
        return s >= 0 ? s % u_frameCount : u_frameCount - 1 - (-(s + 1)) % u_frameCount;
    }
    return clamp(s, 0, u_frameCount - 1);
}

double noiseAt(int i0, int i1, double a, int k) {
    precise double v = (1.0LF - a) * noise[i0 * u_K + k] + a * noise[i1 * u_K + k];
    return v;
}

void main() {
    int j = int(gl_GlobalInvocationID.x);
    if (j >= u_sliceCount) return;

    precise double x = u_tau;
    if (u_F != 0.0LF) {
        precise double T = double(u_T);
        precise double tw = u_tau - T * floor(u_tau / T);   // tau wrapped into [0, T)
        int i0 = int(floor(tw));
        if (i0 >= u_T) i0 -= u_T;                            // rounding at the period end
        precise double a = tw - double(i0);
        int i1 = (i0 + 1) % u_T;
        int k0 = j / 2;
        precise double n = noiseAt(i0, i1, a, k0);
        if ((j & 1) == 1) {                                  // inserted slice: noise at k + 1/2
            precise double n1 = noiseAt(i0, i1, a, k0 + 1);
            n = 0.5LF * (n + n1);
        }
        x = u_tau + u_F * n;
    }
    precise double scaled = x * u_A;
    int s = int(floor(scaled + 0.5LF));                      // eq. (5): nearest integer
    int e = wrapEntry(s);
    int second = int(slotOf[e]);
    float weight = 0.0;
    if (u_linear == 1) {
        // The two stored frames around s and the fraction between (slice_sampler.cpp's blend).
        precise double base = floor(scaled);
        precise double w = scaled - base;
        if (w > 1.0LF - 1e-9LF) {
            base = base + 1.0LF;
            w = 0.0LF;
        } else if (w < 1e-9LF) {
            w = 0.0LF;
        }
        int first = wrapEntry(int(base));
        if (w != 0.0LF) {
            second = int(slotOf[wrapEntry(int(base) + 1)]);
            weight = float(w);
        } else {
            second = int(slotOf[first]);
        }
        slices[j] = ivec2(shownFrame[e], int(slotOf[first]));
    } else {
        slices[j] = ivec2(shownFrame[e], int(slotOf[e]));
    }
    blend[j] = vec2(float(second), weight);
}
