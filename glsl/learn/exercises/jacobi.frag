#version 330 core
// Lesson 2, ping-pong (exercise): one Jacobi step for Laplace's equation on a grid. Every
// interior value becomes the mean of its four neighbours in the previous iterate; the boundary
// keeps its values (Dirichlet). The previous iterate is a texture this pass reads, the next one
// the target it writes: two textures, swapped after each step.

uniform sampler2D u_current; // iterate k
uniform ivec2 u_size;

out float o_value;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float here = texelFetch(u_current, p, 0).r;
    // The boundary is fixed.
    if (p.x == 0 || p.y == 0 || p.x == u_size.x - 1 || p.y == u_size.y - 1) {
        o_value = here;
        return;
    }
    // EXERCISE: write the Jacobi update of an interior value (see the header). As written it
    // copies the value, so nothing moves.
    o_value = here;
}
