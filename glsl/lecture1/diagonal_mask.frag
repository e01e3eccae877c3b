#version 330 core
// Lecture 1, self-collision (a reconstruction on paper 1's streaming AABB test, Sec. 5.2):
// one model's stream against itself. Pair (i, j) and pair (j, i) are the same leaf pair, and
// (i, i) is a leaf against itself, so on a tile of the diagonal only the pairs above it
// (row i < column j) are tested. Drawn after the stencil arrays' pass with stencil op REPLACE
// 0: every pixel on or below the diagonal is cleared, the others keep their mark.

void main() {
    // Pixel (column j, row i) of the tile; centres sit at half-integers.
    int column = int(gl_FragCoord.x);
    int row = int(gl_FragCoord.y);
    if (row < column)
        discard; // above the diagonal: keep the mark of the stencil arrays
}
