#version 330 core
// Lecture 1, a 3D distance field by Hoff et al.'s distance meshes, one z slice at a time:
// every vertex, edge and face of the model draws its distance function over the slice as
// triangles whose height is the distance (a hyperboloid, an elliptic cone, a pair of planes).
// The rasterizer interpolates the distance linearly across each triangle.

layout(location = 0) in vec4 a_vertex; // x, y (pixels of the slice), distance (voxels), unused

uniform vec2 u_size;         // the slice's size in pixels
uniform float u_depth_scale; // 1 / (the deepest mesh vertex, voxels)

out float v_distance;        // voxels

void main() {
    v_distance = a_vertex.z;
    // Orthographic: depth in [0, 1] becomes NDC z in [-1, 1].
    vec2 ndc = a_vertex.xy / u_size * 2.0 - 1.0;
    gl_Position = vec4(ndc, a_vertex.z * u_depth_scale * 2.0 - 1.0, 1.0);
}
