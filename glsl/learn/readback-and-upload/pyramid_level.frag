#version 330 core
// Lesson 8, one level of the histogram pyramid (Ziegler, Tevs, Theobalt & Seidel, "GPU point
// list generation through histogram pyramids", 2006), built over the block flags: each texel
// of a level holds the sum of the 2x2 texels under it, so it counts the flagged blocks below
// it, and the 1x1 top counts them all. The levels are the mipmap levels of one texture; while
// this pass draws level k, only level k - 1 is readable, so texelFetch level 0 reads it.

uniform sampler2D u_below; // the level below: counts in red (level 0: the flags, 1 or 0)

out float o_count;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) * 2;
    // The four children. The pyramid is square, a power of two on a side, so none is missing.
    o_count = (texelFetch(u_below, p, 0).r + texelFetch(u_below, p + ivec2(1, 0), 0).r)
            + (texelFetch(u_below, p + ivec2(0, 1), 0).r + texelFetch(u_below, p + ivec2(1, 1), 0).r);
}
