#version 330 core
// Building block: the facing probe (src/gl/facing.rs). Two triangles in a 2 x 1 target,
// made from gl_VertexID: the first, counter-clockwise in window space, covers the left
// pixel's centre; the second, clockwise, the right pixel's.

const vec2 corners[6] = vec2[6](
    // counter-clockwise, over x in [-1, 0]; the centre (-0.5, 0) is well inside
    vec2(-1.0, -1.0), vec2(0.0, -1.0), vec2(-1.0, 3.0),
    // clockwise, over x in [0, 1]; the centre (0.5, 0) is well inside
    vec2(0.0, -1.0), vec2(0.0, 3.0), vec2(1.0, -1.0));

void main() {
    gl_Position = vec4(corners[gl_VertexID], 0.0, 1.0);
}
