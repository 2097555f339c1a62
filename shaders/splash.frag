#version 450 core
// A splash sprite: a lit droplet disc (sun and sky), soft edge, premultiplied alpha, blended
// in linear RGB (sRGB framebuffer). Everything that does not depend on the pixel (the sky light
// straight up, the drop's light direction) comes in as a uniform: llvmpipe runs this shader
// for tens of thousands of small sprites a frame.
in float v_alpha;
layout(location = 0) out vec4 o_colour;
layout(location = 17) uniform vec3 u_splashColour;
layout(location = 19) uniform vec3 u_ambient;   // the sky straight up (zenithRadiance), linear
layout(location = 20) uniform vec3 u_dropLight; // normalize(u_sunDir + (0, 0, 0.5)), sprite space

void main() {
    const vec2 c = gl_PointCoord * 2.0 - 1.0;
    const float r2 = dot(c, c);
    // No discard outside the disc: the soft edge below is 0 there, which blends to nothing, and
    // without a discard llvmpipe can depth-test before shading.
    // The disc's normal (c.x, -c.y, sqrt(1 - r2)) has unit length inside the disc.
    const float nz = sqrt(max(1.0 - r2, 0.0));
    const float sun = 0.55 + 0.45 * max(dot(vec3(c.x, -c.y, nz), u_dropLight), 0.0);
    const vec3 colour = u_splashColour * (0.45 * u_ambient + 0.75 * sun);
    const float a = v_alpha * smoothstep(1.0, 0.2, r2) * 0.85; // soft, spray-like edge
    o_colour = vec4(colour * a, a); // linear, premultiplied; the framebuffer is sRGB
}
