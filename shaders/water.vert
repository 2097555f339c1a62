#version 450 core
// Sec. 5: the water mesh; the vertices come from surface_vertices.comp (position, normal, the
// refracted colour), so this stage only transforms them.
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_normal;
layout(location = 2) in vec4 a_refracted;

layout(location = 0) uniform mat4 u_viewProj;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_refracted;

void main() {
    v_world = a_position.xyz;
    v_normal = a_normal.xyz;
    v_refracted = a_refracted.rgb;
    gl_Position = u_viewProj * a_position;
}
