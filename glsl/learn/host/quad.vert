#version 330 core
// Host exercises (examples/): the rectangle that covers the viewport, the loop over the
// output array. Its four corners, a triangle strip, come from the vertex's number, so a draw
// needs no vertex buffer: glDrawArrays(GL_TRIANGLE_STRIP, 0, 4) with a vertex array bound
// (a core context draws only with one, even an empty one). Each fragment then runs once per
// pixel of the viewport, and finds its index in gl_FragCoord.

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
