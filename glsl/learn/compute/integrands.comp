#version 430 core
// Lesson 4, compute counterpart: the same eight integrands per cell, written to two storage
// buffers by one invocation. A compute shader writes as many arrays as it binds, at any
// index: the draw-buffer limit of MRT is gone.

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D u_height;
uniform ivec2 u_size;

layout(std430, binding = 0) writeonly buffer First { vec4 b_first[]; };
layout(std430, binding = 1) writeonly buffer Second { vec4 b_second[]; };

void main() {
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    if (cell.x >= u_size.x || cell.y >= u_size.y) return;
    // The cell's centre, as gl_FragCoord gives it to the fragment shader.
    vec2 p = (vec2(cell) + 0.5) / vec2(u_size);
    float z = texelFetch(u_height, cell, 0).r;
    int i = cell.y * u_size.x + cell.x;
    b_first[i] = vec4(z, p.x * z, p.y * z, z * z * 0.5);
    b_second[i] = vec4(p.x * p.x * z, p.y * p.y * z, z * z * z / 3.0, p.x * p.y * z);
}
