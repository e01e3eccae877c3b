#version 430 core
// Lesson 9, the compute counterpart: the vertices written straight into a storage buffer,
// which the draw then reads as its vertex buffer (src/crowd/compute.rs skins the crowd so).

layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer Positions { vec4 b_positions[]; };
uniform int u_n;

void main() {
    int k = int(gl_GlobalInvocationID.x);
    if (k >= u_n * u_n) return;
    vec2 uv = (vec2(k % u_n, k / u_n) + 0.5) / float(u_n);
    float height = 0.25 * sin(6.0 * uv.x) * cos(4.0 * uv.y);
    b_positions[k] = vec4(uv * 2.0 - 1.0, height, 1.0);
}
