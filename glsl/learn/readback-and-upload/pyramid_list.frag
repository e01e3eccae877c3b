#version 330 core
// Lesson 8, the histogram pyramid's traversal (Ziegler et al. 2006): output slot k finds the
// k-th flagged block by walking down from the top. At each level it looks at the four texels
// under its node in a fixed order, (0, 0), (1, 0), (0, 1), (1, 1): it steps into the first
// whose count exceeds k, taking the counts of those it passes off k. At level 0 the node is
// the block. Every slot walks alone, so the list is written in parallel with no counter.

uniform sampler2D u_pyramid; // all levels: level 0 the flags, the top (1x1) the total
uniform int u_top;           // the top level
uniform int u_count;         // flagged blocks: the slots that hold one
uniform int u_width;         // slots per row of this target
uniform int u_blocks_across; // blocks per row of the flags

out float o_block; // the block's index, row by row from the bottom; -1 past the last slot

void main() {
    ivec2 slot = ivec2(gl_FragCoord.xy);
    int k = slot.y * u_width + slot.x;
    if (k >= u_count) {
        o_block = -1.0;
        return;
    }
    ivec2 node = ivec2(0);
    for (int level = u_top - 1; level >= 0; --level) {
        node *= 2;
        // The four children's counts, in the walk's order.
        int a = int(texelFetch(u_pyramid, node, level).r);
        int b = int(texelFetch(u_pyramid, node + ivec2(1, 0), level).r);
        int c = int(texelFetch(u_pyramid, node + ivec2(0, 1), level).r);
        // Step into the first child whose count exceeds k, taking the ones passed off k
        // (the fourth is taken when k passed the other three).
        int child = 0;
        if (k >= a) {
            k -= a;
            child = 1;
            if (k >= b) {
                k -= b;
                child = 2;
                if (k >= c) {
                    k -= c;
                    child = 3;
                }
            }
        }
        node += ivec2(child % 2, child / 2);
    }
    o_block = float(node.y * u_blocks_across + node.x);
}
