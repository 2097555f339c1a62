#version 450 core
// The cube-map environment seen through each pixel (the sky the water reflects, Sec. 5).
in vec2 v_ndc;
layout(location = 0) out vec4 o_colour;
layout(binding = 0) uniform samplerCube u_sky;
layout(location = 0) uniform mat4 u_invViewProj;
layout(location = 4) uniform vec3 u_eye;
void main() {
    const vec4 p = u_invViewProj * vec4(v_ndc, 1.0, 1.0);
    const vec3 dir = p.xyz / p.w - u_eye;
    o_colour = vec4(texture(u_sky, dir).rgb, 1.0); // linear; the framebuffer is sRGB
}
