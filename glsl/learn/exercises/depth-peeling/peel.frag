#version 330 core
// Lesson 7, one peel (Everitt 2001; paper 4, section 3.2, the passes that find each layer
// of the surface). Layer k keeps only the fragments strictly behind the depth layer k-1
// left at their pixel; the ordinary depth test (LESS) then keeps the nearest of those.
// So layer 0 is what the eye sees, layer 1 what lies right behind it, and so on.

uniform sampler2D u_previous_depth; // the depth buffer of layer k-1
uniform int u_layer;                // k: 0 peels nothing
out vec4 o_depth;

void main() {
    float previous = texelFetch(u_previous_depth, ivec2(gl_FragCoord.xy), 0).r;
    // EXERCISE: make each layer after the first keep only what lies behind the one before
    // (see the header). As written nothing is peeled: every layer is layer 0 again, and the
    // peel never ends.

    // The layer's picture: its depth (0 top, 1 bottom of the box).
    o_depth = vec4(gl_FragCoord.z, 0.0, 0.0, 1.0);
}
