#version 330 core
// Lesson 6, a stencil mask selecting where a pass runs (paper 1, section 5.2: the stencil
// buffer masks the pairs of virtual nodes, so the overlap test runs only on real pairs).
// This pass draws no colour: each fragment that survives writes the reference value into
// the stencil buffer; the work pass then runs where the stencil equals it.

uniform sampler2D u_valid; // 1 where the slot holds real data, 0 on the padding

void main() {
    // Padding slots are left unmarked.
    if (texelFetch(u_valid, ivec2(gl_FragCoord.xy), 0).r < 0.5) {
        discard;
    }
}
