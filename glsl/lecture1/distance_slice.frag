#version 330 core
// Lecture 1, distance fields by rasterization (DiFi-style slices, a reconstruction): the
// exact distance from this voxel to one triangle; GL_MIN blending keeps the nearest.
// Compiled after: glsl/lecture1/point_triangle.glsl

uniform sampler2D u_triangles; // as in distance_slice.vert
uniform int u_per_row;
uniform float u_slice;         // z of this slice, voxel units
uniform float u_spacing;       // mesh units per voxel
flat in int v_triangle;
out float o_distance;

vec3 triangle_corner(int t, int c) {
    return texelFetch(u_triangles, ivec2(3 * (t % u_per_row) + c, t / u_per_row), 0).xyz;
}

void main() {
    // The voxel this fragment stands for, in voxel units.
    vec3 p = vec3(gl_FragCoord.xy - 0.5, u_slice);
    int t = v_triangle;
    float d = point_triangle_distance(p, triangle_corner(t, 0), triangle_corner(t, 1),
                                      triangle_corner(t, 2));
    o_distance = d * u_spacing;
}
