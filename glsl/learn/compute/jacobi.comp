#version 430 core
// Lesson 2, compute counterpart: the same Jacobi step between two storage buffers, swapped
// by the caller after each dispatch (with a barrier between, so step k + 1 sees all of k).

layout(local_size_x = 8, local_size_y = 8) in;

uniform ivec2 u_size;

layout(std430, binding = 0) readonly buffer Current { float b_current[]; };
layout(std430, binding = 1) writeonly buffer Next { float b_next[]; };

float at(ivec2 p) {
    return b_current[p.y * u_size.x + p.x];
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y) return;
    float value = at(p);
    // Interior values: the mean of the four neighbours, in the fragment shader's order.
    if (p.x > 0 && p.y > 0 && p.x < u_size.x - 1 && p.y < u_size.y - 1) {
        value = 0.25 * (((at(p - ivec2(1, 0)) + at(p + ivec2(1, 0))) + at(p - ivec2(0, 1)))
                        + at(p + ivec2(0, 1)));
    }
    b_next[p.y * u_size.x + p.x] = value;
}
