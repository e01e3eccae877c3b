#version 330 core
// Lesson 1, a gather: out[k] = values[index[k]]. A fragment may read any texel (an indirect
// read), but writes only its own pixel: reading anywhere is free, writing anywhere is not
// (that is scatter, lesson 5).

uniform sampler2D u_values;
uniform sampler2D u_index; // element k holds the index to read, an integer stored in a float
uniform int u_width;       // texels per row of u_values

out float o_value;

void main() {
    // Which index this element reads (exact: integers below 2^24 are exact in fp32).
    int k = int(texelFetch(u_index, ivec2(gl_FragCoord.xy), 0).r);
    // The 1D index as a 2D texel, row-major from the bottom.
    o_value = texelFetch(u_values, ivec2(k % u_width, k / u_width), 0).r;
}
