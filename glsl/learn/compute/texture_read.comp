#version 430 core
// Lesson 0, compute counterpart: the same texture read by index from a compute shader, one
// invocation per texel, into a storage buffer (an array the CPU reads without a target).

layout(local_size_x = 64) in;

uniform sampler2D u_input;
uniform ivec2 u_size; // texels per row, rows

layout(std430, binding = 0) writeonly buffer Values { float b_values[]; };

void main() {
    // The invocation's index is the element's index; the grid may overshoot the array.
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_size.x * u_size.y) return;
    // Row-major, rows from the bottom: the order glGetTexImage returns.
    ivec2 texel = ivec2(i % u_size.x, i / u_size.x);
    b_values[i] = texelFetch(u_input, texel, 0).r;
}
