#version 330 core
// Lesson 1, a quad is a loop (exercise): y = a x + y for every element at once. The rectangle
// drawn over the target is the loop `for each (i, j)`; this shader is the loop's body, run once
// per fragment, reading x and y at the fragment's own index and writing the new y there.

uniform sampler2D u_x;
uniform sampler2D u_y;
uniform float u_a;

out float o_y;

void main() {
    // The loop index: the fragment's pixel.
    ivec2 i = ivec2(gl_FragCoord.xy);
    float x = texelFetch(u_x, i, 0).r;
    float y = texelFetch(u_y, i, 0).r;
    // EXERCISE: the body copies y; make it compute a x + y.
    o_y = y;
}
