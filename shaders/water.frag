#version 450 core
// Sec. 5: water shaded with the environment cube map: reflection, refraction (the
// depth-dependent colour along the refracted ray, from surface_vertices.comp) and the Fresnel effect
// (Schlick's approximation), plus a sun highlight. Linear RGB; the framebuffer is sRGB.

in vec3 v_world;
in vec3 v_normal;
in vec3 v_refracted;
layout(location = 0) out vec4 o_colour;

layout(binding = 0) uniform samplerCube u_sky;
layout(location = 4) uniform vec3 u_eye;
layout(location = 5) uniform vec3 u_sunDir; // unit vector towards the sun
layout(location = 11) uniform float u_f0;   // Schlick's F0 = ((n - 1) / (n + 1))^2
layout(location = 12) uniform vec2 u_sun;   // highlight exponent, intensity
layout(location = 13) uniform vec3 u_sunColour;
layout(location = 18) uniform float u_reflectionLod; // fixed cube-map level (no derivatives)

void main() {
    vec3 N = normalize(v_normal);
    const vec3 V = normalize(u_eye - v_world);
    if (dot(N, V) < 0.0) N = normalize(N - 1.01 * dot(N, V) * V); // silhouette: face the eye
    const float cosV = clamp(dot(N, V), 0.0, 1.0);

    // Reflection of the environment.
    vec3 R = reflect(-V, N);
    R.y = abs(R.y); // a reflected ray into the water would hit the surface again: take the sky
    const vec3 reflected = textureLod(u_sky, R, u_reflectionLod).rgb;

    // Fresnel, Schlick's approximation: F0 + (1 - F0) (1 - cos)^5.
    const float c = 1.0 - cosV;
    const float c2 = c * c;
    const float F = u_f0 + (1.0 - u_f0) * (c2 * c2 * c);
    // Sun highlight (Phong lobe around the reflected ray), weighted by Fresnel.
    const float lobe = pow(max(dot(R, u_sunDir), 0.0), u_sun.x);
    const vec3 highlight = u_sunColour * u_sun.y * lobe * (0.25 + F);

    o_colour = vec4(mix(v_refracted, reflected, F) + highlight, 1.0);
}
