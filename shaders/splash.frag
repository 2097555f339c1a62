#version 450 core
// A splash sprite: a lit droplet disc (sun and sky), soft edge, premultiplied alpha, blended
// in linear RGB (sRGB framebuffer).
in float v_alpha;
layout(location = 0) out vec4 o_colour;
layout(binding = 0) uniform samplerCube u_sky;
layout(location = 5) uniform vec3 u_sunDir;
layout(location = 17) uniform vec3 u_splashColour;

void main() {
    const vec2 c = gl_PointCoord * 2.0 - 1.0;
    const float r2 = dot(c, c);
    if (r2 > 1.0) discard;
    const float nz = sqrt(1.0 - r2);
    const vec3 ambient = texture(u_sky, vec3(0.0, 1.0, 0.0)).rgb;
    const float sun = 0.55 + 0.45 * max(dot(normalize(vec3(c.x, -c.y, nz)), normalize(u_sunDir + vec3(0.0, 0.0, 0.5))), 0.0);
    const vec3 colour = u_splashColour * (0.45 * ambient + 0.75 * sun);
    const float a = v_alpha * smoothstep(1.0, 0.2, r2) * 0.85; // soft, spray-like edge
    o_colour = vec4(colour * a, a); // linear, premultiplied; the framebuffer is sRGB
}
