#version 330 core
// Lesson 8, after the histogram pyramid's list (Ziegler et al. 2006): the flagged blocks
// gathered into one small texture, one tile per slot of the list in the list's layout, so
// that a single glReadPixels returns their texels and nothing else. A fragment finds its tile,
// the block the list names there, and copies the matching texel of that block.

uniform sampler2D u_data; // the whole array (RGBA32F)
uniform sampler2D u_list; // the list: the block index of each slot, -1 past the last
uniform int u_block;      // block side in texels
uniform int u_blocks_across; // blocks per row of the array

out vec4 o_value;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float block = texelFetch(u_list, p / u_block, 0).r;
    if (block < 0.0) {
        o_value = vec4(0.0);
        return;
    }
    int b = int(block);
    ivec2 corner = ivec2(b % u_blocks_across, b / u_blocks_across) * u_block;
    o_value = texelFetch(u_data, corner + p % u_block, 0);
}
