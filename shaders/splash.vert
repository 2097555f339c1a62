#version 450 core
// Sec. 5: splash particles (real and artificial) as point sprites of a fixed world radius.
layout(location = 0) in vec4 a_sprite; // x, y, z (metres), opacity

layout(location = 0) uniform mat4 u_viewProj;
layout(location = 15) uniform float u_pixelsPerMetre; // at unit distance: height / (2 tan(fov/2))
layout(location = 16) uniform float u_radius;         // sprite radius, metres

out float v_alpha;

void main() {
    gl_Position = u_viewProj * vec4(a_sprite.xyz, 1.0);
    gl_PointSize = clamp(2.0 * u_radius * u_pixelsPerMetre / max(gl_Position.w, 1e-4), 1.0, 64.0);
    v_alpha = a_sprite.w;
}
