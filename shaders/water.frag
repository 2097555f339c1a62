#version 450 core
// Sec. 5: water shaded with the environment cube map: reflection, refraction (the
// depth-dependent colour along the refracted ray) and the Fresnel effect (Schlick's
// approximation), plus a sun highlight. Linear RGB; the framebuffer is sRGB.
//
// The reflected environment, the refracted colour and the Fresnel weight vary slowly over the
// surface and come per vertex from surface_vertices.comp, already mixed (v_shade.rgb) with the
// Fresnel weight in v_shade.a. Only the narrow sun highlight (a Phong lobe of exponent ~900,
// narrower than a mesh cell) is evaluated per pixel, around the interpolated reflected ray
// (the view direction barely changes over a triangle, so this is the interpolated normal's
// reflection). On llvmpipe, whose small triangles shade whole 4 x 4 pixel blocks and set up
// every interpolated value per triangle, both the work here and the varyings are kept few.

in vec3 v_reflected;
in vec4 v_shade; // mix(refracted, reflected, F) (linear RGB), F
layout(location = 0) out vec4 o_colour;

layout(location = 5) uniform vec3 u_sunDir; // unit vector towards the sun
layout(location = 12) uniform vec2 u_sun;   // highlight exponent, intensity
layout(location = 13) uniform vec3 u_sunColour;

void main() {
    const vec3 R = normalize(v_reflected);
    const float lobe = pow(max(dot(R, u_sunDir), 0.0), u_sun.x);
    o_colour = vec4(v_shade.rgb + u_sunColour * (u_sun.y * lobe * (0.25 + v_shade.a)), 1.0);
}
