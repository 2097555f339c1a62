#version 450 core
// Sec. 5: water shaded with the environment cube map: reflection, refraction and the Fresnel
// effect (Schlick's approximation), a sun highlight, and a depth-dependent colour along the
// refracted ray (Beer-Lambert absorption down to the bed and in-scattering). Lighting in
// linear RGB; the output is gamma encoded (2.2).

in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_colour;

layout(binding = 0) uniform samplerCube u_sky;
layout(location = 4) uniform vec3 u_eye;
layout(location = 5) uniform vec3 u_sunDir;     // unit vector towards the sun
layout(location = 6) uniform float u_bedY;      // bed height (domain yMin), metres
layout(location = 7) uniform vec3 u_absorption; // per metre, per channel
layout(location = 8) uniform vec3 u_scatter;    // colour of light scattered by deep water
layout(location = 9) uniform vec3 u_bed;        // bed albedo
layout(location = 10) uniform float u_eta;      // n_air / n_water
layout(location = 11) uniform float u_f0;       // Schlick's F0 = ((n - 1) / (n + 1))^2
layout(location = 12) uniform vec2 u_sun;       // highlight exponent, intensity
layout(location = 13) uniform vec3 u_sunColour;
layout(location = 18) uniform float u_reflectionLod; // fixed cube-map level (no derivatives: llvmpipe)

void main() {
    vec3 N = normalize(v_normal);
    const vec3 V = normalize(u_eye - v_world);
    if (dot(N, V) < 0.0) N = normalize(N - 1.01 * dot(N, V) * V); // silhouette: face the eye
    const float cosV = clamp(dot(N, V), 0.0, 1.0);

    // Reflection of the environment.
    vec3 R = reflect(-V, N);
    R.y = abs(R.y); // a reflected ray into the water would hit the surface again: take the sky
    const vec3 reflected = textureLod(u_sky, R, u_reflectionLod).rgb;

    // Refraction: the ray goes down to the bed; light is absorbed along the path and
    // scattered in, so deep water tends to u_scatter and shallow water shows the bed.
    const vec3 T = refract(-V, N, u_eta);
    const float depth = max(v_world.y - u_bedY, 0.0);
    const float path = T.y < -1e-3 ? depth / -T.y : 20.0 * depth + 1.0;
    const vec3 transmit = exp(-u_absorption * path);
    const float sunDown = max(u_sunDir.y, 0.15);
    const vec3 bedLit = u_bed * (0.25 + 0.75 * sunDown) * exp(-u_absorption * depth / sunDown);
    const vec3 refracted = bedLit * transmit + u_scatter * (1.0 - transmit);

    // Fresnel, Schlick's approximation.
    const float F = u_f0 + (1.0 - u_f0) * pow(1.0 - cosV, 5.0);
    // Sun highlight (Phong lobe around the reflected ray), weighted by Fresnel.
    const float lobe = pow(max(dot(R, u_sunDir), 0.0), u_sun.x);
    const vec3 highlight = u_sunColour * u_sun.y * lobe * (0.25 + F);

    const vec3 colour = mix(refracted, reflected, F) + highlight;
    o_colour = vec4(pow(clamp(colour, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
