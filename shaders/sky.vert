#version 450 core
// The environment behind everything: one full-screen triangle.
out vec2 v_ndc;
void main() {
    const vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
    v_ndc = p;
    gl_Position = vec4(p, 1.0, 1.0);
}
