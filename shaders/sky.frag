#version 450 core
// The environment seen through each pixel: the cube-map sky (the sky the water reflects,
// Sec. 5) and, below the horizon, the floor the water block stands on: a tiled sand-stone plane
// at the bed height, lit by the sun and the sky, shadowed by the block (the sun's light
// absorbed along its path through the water, Beer-Lambert), darkened next to the block's foot,
// and fading with distance into the horizon of the sky behind it. The water is always in front
// of the floor (both stand on the plane, the eye above it), so the floor needs no depth.
in vec2 v_ndc;
layout(location = 0) out vec4 o_colour;
layout(binding = 0) uniform samplerCube u_sky;
layout(location = 0) uniform mat4 u_invViewProj;
layout(location = 4) uniform vec3 u_eye;
layout(location = 5) uniform vec3 u_sunDir;       // unit vector towards the sun
layout(location = 6) uniform float u_floorY;      // the floor's (and the bed's) height, metres
layout(location = 7) uniform vec3 u_absorption;   // of the water, per metre
layout(location = 9) uniform vec3 u_floorColour;  // albedo, linear RGB
layout(location = 22) uniform vec4 u_floor;       // tile size (m), contrast, haze distance (m), on
layout(location = 23) uniform vec4 u_block;       // the block's footprint: x0, z0, x1, z1 (m)
layout(location = 24) uniform float u_blockTop;   // its still-water level, metres

// Per-tile value in [0, 1).
float tileHash(vec2 cell) {
    return fract(sin(dot(cell, vec2(127.1, 311.7))) * 43758.5453);
}

// Length of the segment of the ray p + s d (s > 0) inside the block (axis-aligned box).
float pathInBlock(vec3 p, vec3 d) {
    const vec3 lo = vec3(u_block.x, u_floorY, u_block.y);
    const vec3 hi = vec3(u_block.z, u_blockTop, u_block.w);
    const vec3 inv = 1.0 / d;
    const vec3 t0 = (lo - p) * inv, t1 = (hi - p) * inv;
    const vec3 tn = min(t0, t1), tf = max(t0, t1);
    const float enter = max(max(tn.x, tn.y), max(tn.z, 0.0));
    const float leave = min(min(tf.x, tf.y), tf.z);
    return max(leave - enter, 0.0);
}

// The floor at `p`; `w`: the pixel's footprint in tiles (fwidth of p.xz / tile size).
vec3 floorColour(vec3 p, vec2 w) {
    // Tiles: each a little brighter or darker, with dark joints; the pattern fades out where a
    // pixel spans a good part of a tile (no aliasing towards the horizon).
    const vec2 uv = p.xz / u_floor.x;
    const float detail = 1.0 - smoothstep(0.15, 0.6, max(w.x, w.y));
    const vec2 f = fract(uv);
    const vec2 edge = min(f, 1.0 - f);
    const vec2 joint = 1.0 - smoothstep(vec2(0.02), vec2(0.02) + max(w, vec2(1e-4)), edge);
    const float jointMask = max(joint.x, joint.y);
    const float tile = 1.0 + u_floor.y * (tileHash(floor(uv)) - 0.5);
    const float pattern = mix(1.0, tile * (1.0 - 0.45 * jointMask), detail);
    // Sun through the block (its still-water box): the light absorbed along the path.
    const vec3 sunThrough = exp(-u_absorption * pathInBlock(p, u_sunDir));
    // Ambient occlusion at the block's foot: the distance to its footprint's boundary.
    const vec2 c = 0.5 * (u_block.xy + u_block.zw), r = 0.5 * (u_block.zw - u_block.xy);
    const vec2 q = abs(p.xz - c) - r;
    const float outside = length(max(q, 0.0)) + min(max(q.x, q.y), 0.0);
    const float height = max(u_blockTop - u_floorY, 1e-3);
    const float occlusion = 1.0 - 0.45 * exp(-max(outside, 0.0) / (0.25 * height));
    // The lighting of the bed seen through the water (surface_vertices.comp): sky and sun.
    const float sunDown = max(u_sunDir.y, 0.15);
    const vec3 light = vec3(0.25 * occlusion) + 0.75 * sunDown * sunThrough;
    return u_floorColour * pattern * light;
}

void main() {
    const vec4 p = u_invViewProj * vec4(v_ndc, 1.0, 1.0);
    const vec3 dir = normalize(p.xyz / p.w - u_eye);
    vec3 colour = texture(u_sky, dir).rgb; // linear; the framebuffer is sRGB
    // Where the ray meets the floor (derivatives taken in uniform control flow: every pixel).
    const float eyeHeight = u_eye.y - u_floorY;
    const float s = eyeHeight / max(-dir.y, 1e-6);
    const vec3 hit = u_eye + s * dir;
    const vec2 w = fwidth(hit.xz / u_floor.x);
    if (u_floor.w > 0.5 && eyeHeight > 0.0 && dir.y < 0.0) {
        const vec3 horizon = textureLod(u_sky, normalize(vec3(dir.x, 0.0, dir.z)), 0.0).rgb;
        const float haze = 1.0 - exp(-s / u_floor.z);
        colour = mix(floorColour(hit, w), horizon, haze);
    }
    o_colour = vec4(colour, 1.0);
}
