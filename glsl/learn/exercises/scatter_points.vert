#version 330 core
// Lesson 5, scatter by points (exercise): one point per value (gl_VertexID, no vertex buffer).
// The vertex shader reads the value from a texture and places the point on the pixel of the
// value's bin in a bins x 1 target: the vertex stage can write anywhere, which a fragment
// cannot. The blending unit then adds each point's 1 to what the bin holds.

uniform sampler2D u_values; // the values in [0, 1), row-major from the bottom
uniform int u_width;        // texels per row of u_values
uniform int u_bins;

void main() {
    // The value this point stands for.
    ivec2 texel = ivec2(gl_VertexID % u_width, gl_VertexID / u_width);
    float value = texelFetch(u_values, texel, 0).r;
    // EXERCISE: every point lands in bin 0. Compute the bin the value falls in (u_bins equal
    // bins over [0, 1)).
    float bin = 0.0;
    // The bin's pixel centre in clip space: x from -1 to 1 across the row.
    gl_Position = vec4((bin + 0.5) / float(u_bins) * 2.0 - 1.0, 0.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
