#version 330 core
// Lecture 3, debugging tip "simplify code with alpha blending": the histogram without blending,
// for comparison.
// The histogram without blending, for comparison: each bin's pixel reads every value and
// adds those that fall in it (bins x values reads, and a loop the blending version does not
// need). llvmpipe ends a shader's loops after 65535 iterations in all, so the caller keeps
// the count within that.

uniform sampler2D u_values;
uniform sampler2D u_weights;
uniform bool u_weighted;
uniform int u_columns;    // the value texture's width
uniform int u_count;      // values
uniform float u_lo;
uniform float u_scale;
uniform int u_bins;

out float o_sum;

void main() {
    float bin = floor(gl_FragCoord.x);
    float sum = 0.0;
    for (int i = 0; i < u_count; ++i) {
        ivec2 texel = ivec2(i % u_columns, i / u_columns);
        float t = (texelFetch(u_values, texel, 0).r - u_lo) * u_scale;
        if (t >= 0.0 && t < float(u_bins) && floor(t) == bin) {
            sum += u_weighted ? texelFetch(u_weights, texel, 0).r : 1.0;
        }
    }
    o_sum = sum;
}
