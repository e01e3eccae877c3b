#version 330 core
// Test of a building block: render to a vertex buffer through a PBO (paper 2's pass 1).
// Writes, for texel i, the clip-space position of a point: the pixel centre of texel i of
// a w x h grid mapped into a (2w) x (2h) target, doubled. Read into a vertex buffer, these
// positions light exactly the pixels (2x+1, 2y+1).
uniform vec2 u_target;
out vec4 o_position;

void main() {
    vec2 pixel = floor(gl_FragCoord.xy) * 2.0 + 1.5;
    o_position = vec4(pixel / u_target * 2.0 - 1.0, 0.0, 1.0);
}
