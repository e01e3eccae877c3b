#version 330 core
// Lesson 4, several outputs: one pass writes two render targets (MRT). For a height field
// z(x, y) over the unit square, each texel's column [0, z] has eight integrands of the
// volume's moments; a fragment computes them all once and writes four to each target, where
// two single-target passes would read and compute everything twice.

uniform sampler2D u_height; // z at each cell
uniform vec2 u_size;        // cells per side

layout(location = 0) out vec4 o_first;  // z, x z, y z, z^2 / 2
layout(location = 1) out vec4 o_second; // x^2 z, y^2 z, z^3 / 3, x y z

void main() {
    // The cell's centre in the unit square, and its height.
    vec2 p = gl_FragCoord.xy / u_size;
    float z = texelFetch(u_height, ivec2(gl_FragCoord.xy), 0).r;
    // Target 0: the volume integrand and the first moments.
    o_first = vec4(z, p.x * z, p.y * z, z * z * 0.5);
    // Target 1: the second moments.
    o_second = vec4(p.x * p.x * z, p.y * p.y * z, z * z * z / 3.0, p.x * p.y * z);
}
