#version 330 core
// Test of a building block: vertex texture fetch (see glsl/test/vertex_fetch.vert).
// Writes the value the vertex shader read.
in vec4 v_value;
out vec4 o_value;

void main() {
    o_value = v_value;
}
