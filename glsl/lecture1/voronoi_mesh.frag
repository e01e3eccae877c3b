#version 330 core
// Lecture 1, generalized Voronoi diagrams by distance meshes (Hoff et al. 1999): the depth
// test (LESS, sites in id order) has already kept the nearest mesh; the colour stores the
// site id and the interpolated distance. No gl_FragDepth: the depth is the mesh's own.

uniform float u_pixel;   // input units per pixel
in float v_distance;     // pixels
flat in int v_site;
out vec4 o_site;         // site id, distance (input units)

void main() {
    // A pixel centre the rasterizer counts inside a triangle it lies a hair outside of
    // reads the triangle's plane extended, which beside a segment dips below 0.
    o_site = vec4(float(v_site), max(v_distance, 0.0) * u_pixel, 0.0, 1.0);
}
