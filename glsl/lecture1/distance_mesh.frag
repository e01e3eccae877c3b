#version 330 core
// Lecture 1, a 3D distance field by distance meshes: the depth test (LESS) has already kept
// the nearest feature's mesh; the colour stores its interpolated distance. No gl_FragDepth:
// the depth is the mesh's own.

in float v_distance;     // voxels
out vec4 o_distance;     // distance (voxels) in red

void main() {
    // A pixel centre the rasterizer counts inside a triangle it lies a hair outside of
    // reads the triangle's plane extended, which beside a face dips below 0.
    o_distance = vec4(max(v_distance, 0.0), 0.0, 0.0, 1.0);
}
