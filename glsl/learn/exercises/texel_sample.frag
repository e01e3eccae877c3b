#version 330 core
// Lesson 0, texel centres (exercise): sample one row of N texels with texture() (normalised
// coordinates, linear filtering) at a chosen point of texel i. Texel i covers [i/N, (i+1)/N);
// a point on the border between two texels gets half of each under linear filtering (texel 0
// clamps to the edge and gives its own value).

uniform sampler2D u_input; // one row, GL_LINEAR
uniform vec2 u_size;       // the row's size in texels (N, 1)
uniform float u_offset;    // where in the texel: 0.5 its centre, 0.0 its left edge

out float o_value;

void main() {
    // Which element this fragment computes.
    float i = floor(gl_FragCoord.x);
    // EXERCISE: this always samples the texel's left edge, whatever u_offset asks for. Sample
    // the point u_offset of the way into texel i.
    float x = i / u_size.x;
    // The row's one texel row has its centre at y = 0.5.
    o_value = texture(u_input, vec2(x, 0.5)).r;
}
