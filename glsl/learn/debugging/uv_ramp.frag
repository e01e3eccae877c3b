#version 330 core
// Lesson 11, debugging: the rectangle's coordinate written out as it arrives. The rectangle's
// vertex shader (glsl/gl/rect.vert) writes the varying v_uv; this stage must read a varying of
// that very name and type, or the program does not link (or, where a desktop driver only warns,
// reads an input nothing wrote). The lesson renames it on purpose.

in vec2 v_uv; // 0..1 across the rectangle, interpolated to the fragment's centre

out vec4 o_value;

void main() {
    o_value = vec4(v_uv, 0.0, 0.0);
}
