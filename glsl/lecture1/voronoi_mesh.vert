#version 330 core
// Lecture 1, generalized Voronoi diagrams by distance meshes (Hoff et al. 1999): each site's
// distance function as triangles whose depth is the distance (a cone for a point, a tent
// for a segment, a flat top inside a triangle). The rasterizer interpolates the depth
// linearly across each triangle, so the mesh is exact where the distance function is
// planar and within the stated tessellation bound on the cones.

layout(location = 0) in vec4 a_vertex; // x, y (pixels from the domain's corner), distance (pixels), site id

uniform vec2 u_size;         // the target's size in pixels
uniform float u_depth_scale; // 1 / (the deepest mesh vertex, pixels)

out float v_distance;        // pixels
flat out int v_site;

void main() {
    v_site = int(a_vertex.w);
    v_distance = a_vertex.z;
    // Orthographic: depth in [0, 1] becomes NDC z in [-1, 1].
    vec2 ndc = a_vertex.xy / u_size * 2.0 - 1.0;
    gl_Position = vec4(ndc, a_vertex.z * u_depth_scale * 2.0 - 1.0, 1.0);
}
