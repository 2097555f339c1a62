#version 450 core
// Copies the cached environment background (the sky pass rendered once per camera) into a
// multisampled framebuffer, where a framebuffer blit is not allowed. Both are sRGB: decoding
// and encoding 8-bit sRGB round-trips exactly.
layout(location = 0) out vec4 o_colour;
layout(binding = 1) uniform sampler2D u_background;
void main() { o_colour = texelFetch(u_background, ivec2(gl_FragCoord.xy), 0); }
