#version 330 core
// Lesson 6, counting with an occlusion query (paper 1, section 5.2: the query counts the
// colliding pairs the overlap pass leaves; lecture 3's debugging tips). A fragment that
// survives is one sample the query counts; a discarded one is not counted.

uniform sampler2D u_values; // the array, one float per texel
uniform float u_threshold;  // count the values strictly above it
out vec4 o_colour;

void main() {
    // Read this pixel's element: texel centre, no filtering.
    float value = texelFetch(u_values, ivec2(gl_FragCoord.xy), 0).r;
    // The condition: a value at or below the threshold is not counted.
    if (value <= u_threshold) {
        discard;
    }
    // What is written does not matter to the count; white shows where it counted.
    o_colour = vec4(1.0);
}
