#version 450 core
// Sec. 5: the water mesh; the vertices come from surface_vertices.comp (position, the reflected
// view ray, the shaded colour without the sun highlight and the Fresnel weight), so this stage
// only transforms them.
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_reflected;
layout(location = 2) in vec4 a_shade;

layout(location = 0) uniform mat4 u_viewProj;

out vec3 v_reflected;
out vec4 v_shade;

void main() {
    v_reflected = a_reflected.xyz;
    v_shade = a_shade;
    gl_Position = u_viewProj * a_position;
}
