#version 450 core
// A side of the water block, seen through a glass wall: light from above absorbed with depth
// below the local surface (Beer-Lambert) plus in-scattering, a faint sky reflection. Linear
// RGB; the framebuffer is sRGB.

in vec3 v_world;
in float v_surface;
flat in vec3 v_normal;
layout(location = 0) out vec4 o_colour;

layout(binding = 0) uniform samplerCube u_sky;
layout(location = 4) uniform vec3 u_eye;
layout(location = 5) uniform vec3 u_sunDir;
layout(location = 7) uniform vec3 u_absorption;
layout(location = 8) uniform vec3 u_scatter;
layout(location = 11) uniform float u_f0;
layout(location = 19) uniform vec3 u_ambient; // the sky straight up (zenithRadiance), linear

void main() {
    const float below = max(v_surface - v_world.y, 0.0);
    const vec3 down = exp(-u_absorption * below);
    const vec3 lit = u_ambient * (0.35 + 0.65 * max(u_sunDir.y, 0.0));
    vec3 colour = u_scatter * (1.0 - down) + lit * 0.6 * down * vec3(0.55, 0.85, 0.9);
    const vec3 V = normalize(u_eye - v_world);
    const float F = u_f0 + (1.0 - u_f0) * pow(1.0 - clamp(abs(dot(v_normal, V)), 0.0, 1.0), 5.0);
    colour = mix(colour, texture(u_sky, reflect(-V, v_normal)).rgb, F);
    o_colour = vec4(colour, 1.0); // linear; the framebuffer is sRGB
}
