#version 430 core
// Lesson 1, compute counterpart: y = a x + y over storage buffers. The loop is now the grid
// of invocations, and y is read and written in place: each invocation owns its element.

layout(local_size_x = 64) in;

uniform float u_a;
uniform uint u_count;

layout(std430, binding = 0) readonly buffer X { float b_x[]; };
layout(std430, binding = 1) buffer Y { float b_y[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    // The grid is a whole number of groups: the last may overshoot the array.
    if (i >= u_count) return;
    b_y[i] = u_a * b_x[i] + b_y[i];
}
