// Depth peeling (Everitt 2001; paper 4 section 3.2), as a snippet for any fragment shader
// taking part: call peel_discard() first. Layer k keeps only fragments strictly behind the
// depth that layer k-1 stored; the depth test (LESS) then keeps the nearest of those.

uniform sampler2D u_peel_depth; // the previous layer's depth
uniform int u_peel_layer;       // 0 for the first layer, which peels nothing

void peel_discard() {
    if (u_peel_layer > 0 &&
        gl_FragCoord.z <= texelFetch(u_peel_depth, ivec2(gl_FragCoord.xy), 0).r) {
        discard;
    }
}
