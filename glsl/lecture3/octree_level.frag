#version 330 core
// Lecture 3, "octrees and quadtrees on the GPU" (reconstructed; src/lecture3/octree/levels.rs):
// one level of the occupancy octree from the level below.
// Each texel is node (i, j, l) of an n^3 level whose z slices are tiled side by side (tile
// (l % tx, l / tx)); the node is occupied when any of its eight children in the level below
// (2n)^3 is. Texels of unused tiles hold 0.

uniform sampler2D u_below;   // the level below, tiled the same way
uniform int u_n;             // this level's side
uniform ivec2 u_tiles;       // this level's tiles per row and rows
uniform ivec2 u_below_tiles; // the level below's

out vec4 o_value;

// Where voxel v of an n^3 level with `tiles` lies in its texture.
ivec2 texel(ivec3 v, int n, ivec2 tiles) {
    return v.xy + ivec2(v.z % tiles.x, v.z / tiles.x) * n;
}

void main() {
    // Which node this texel is.
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 tile = p / u_n;
    int l = tile.y * u_tiles.x + tile.x;
    if (l >= u_n) {
        o_value = vec4(0.0);
        return;
    }
    ivec3 node = ivec3(p - tile * u_n, l);
    // Any of the eight children occupied.
    float any = 0.0;
    for (int c = 0; c < 8; ++c) {
        ivec3 child = 2 * node + ivec3(c & 1, (c >> 1) & 1, c >> 2);
        any = max(any, texelFetch(u_below, texel(child, 2 * u_n, u_below_tiles), 0).r);
    }
    o_value = vec4(any, 0.0, 0.0, 0.0);
}
