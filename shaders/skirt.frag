#version 450 core
// A side of the water block, seen through a glass wall: light from above absorbed with depth
// below the local surface (Beer-Lambert) plus in-scattering, and the faint sky reflection
// (skirt.vert). Linear RGB; the framebuffer is sRGB.

in float v_below;
in vec4 v_reflection; // rgb: F x reflected sky, a: F
layout(location = 0) out vec4 o_colour;

layout(location = 7) uniform vec3 u_absorption;
layout(location = 8) uniform vec3 u_scatter;
layout(location = 21) uniform vec3 u_sideLight; // light from above entering a side, linear

void main() {
    const vec3 down = exp(-u_absorption * max(v_below, 0.0));
    const vec3 colour = u_scatter * (1.0 - down) + u_sideLight * down;
    o_colour = vec4(colour * (1.0 - v_reflection.a) + v_reflection.rgb, 1.0);
}
