#version 430 core
// Lecture 1, distance fields (then and now): the compute counterpart of the slice passes.
// Compiled after: glsl/lecture1/point_triangle.glsl
// One invocation per voxel runs over every triangle and keeps the nearest: no rectangles,
// no blending, no slices read back one by one; the field is written straight into a storage
// buffer in [z][y][x] order. Voxel units as in the slice passes.

layout(local_size_x = 64) in;

// Corners of triangle t at 3 t, 3 t + 1, 3 t + 2 (xyz; w unused).
layout(std430, binding = 0) readonly buffer Corners { vec4 b_corners[]; };
layout(std430, binding = 1) writeonly buffer Field { float b_field[]; };

uniform uint u_n;          // voxels per axis
uniform uint u_triangles;  // triangle count
uniform uint u_first;      // the first voxel of this dispatch
uniform float u_spacing;   // mesh units per voxel
uniform float u_clamp;     // mesh units; the largest float when there is none

void main() {
    uint i = u_first + gl_GlobalInvocationID.x;
    if (i >= u_n * u_n * u_n) return;
    vec3 p = vec3(float(i % u_n), float((i / u_n) % u_n), float(i / (u_n * u_n)));
    float best = 3.402823e38;
    for (uint t = 0u; t < u_triangles; ++t) {
        best = min(best, point_triangle_distance(p, b_corners[3u * t].xyz,
                                                 b_corners[3u * t + 1u].xyz,
                                                 b_corners[3u * t + 2u].xyz));
    }
    b_field[i] = min(best * u_spacing, u_clamp);
}
