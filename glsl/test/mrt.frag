#version 330 core
// Test of a building block: several render targets in one pass (paper 4's integrands).
// Three render targets written in one pass, each a different function of the pixel.
layout(location = 0) out vec4 o_first;
layout(location = 1) out vec4 o_second;
layout(location = 2) out vec4 o_third;

void main() {
    vec2 p = floor(gl_FragCoord.xy);
    o_first = vec4(p.x, p.y, 1.0, 2.0);
    o_second = vec4(p.x * p.y, -p.x, 0.5, 3.0);
    o_third = vec4(p.x + 100.0 * p.y, 7.0, -1.0, 4.0);
}
