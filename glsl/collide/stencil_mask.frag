#version 330 core
// Paper 1 (Zhang & Kim 2007), section 4.2.1 "1D AABB Textures" (the stencil arrays) used in 5.2
// step 1: the prevented pairs (PAPs).
// Filling the stencil buffer from the two 1D stencil arrays (Sec. 4.2.1, Fig. 5): the pair of
// slots (i, j) survives only when both are marked 1 (a real leaf, or the first copy of a
// pulled-down leaf). Drawn with stencil op REPLACE 1; discarded pairs keep 0 and become
// prevented AABB pairs (PAPs) in the overlap pass.

in vec2 v_uv;
uniform sampler1D u_stencil_a; // rows: S^X
uniform sampler1D u_stencil_b; // columns: S^Y

// region: stencil-mask
void main() {
    if (texture(u_stencil_a, v_uv.y).r < 0.5 || texture(u_stencil_b, v_uv.x).r < 0.5)
        discard;
}
// endregion
