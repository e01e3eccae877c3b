#version 330 core
// Lesson 9, pass 2: the vertex buffer that pass 1 filled, drawn as points. Each vertex lands
// on the pixel centre its x, y name and carries its height to the fragment shader, so the
// picture is the height field, checked pixel by pixel against the CPU.

layout(location = 0) in vec4 a_position; // read from the buffer the fragment pass wrote
out float v_height;

void main() {
    v_height = a_position.z;
    gl_Position = vec4(a_position.xy, 0.0, 1.0);
}
