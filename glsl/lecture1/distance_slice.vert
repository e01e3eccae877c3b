#version 330 core
// Lecture 1, distance fields by rasterization (DiFi-style slices, a reconstruction): the
// screen rectangle of one triangle in one z slice, grown by the clamp distance.
// Instance t draws triangle t as a four-corner strip. Coordinates are voxel units: voxel
// (x, y, z) is the point (x, y, z), pixel (x, y) of the slice has its centre at (x + 0.5,
// y + 0.5) in window coordinates.

uniform sampler2D u_triangles; // corner c of triangle t: texel (3 (t % u_per_row) + c, t / u_per_row)
uniform int u_per_row;
uniform float u_slice;         // z of this slice, voxel units
uniform float u_bound;         // the clamp distance, voxel units; negative: no clamp
uniform vec2 u_size;           // the slice, pixels
flat out int v_triangle;

vec3 corner(int t, int c) {
    return texelFetch(u_triangles, ivec2(3 * (t % u_per_row) + c, t / u_per_row), 0).xyz;
}

void main() {
    int t = gl_InstanceID;
    v_triangle = t;
    vec3 a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
    vec2 lo = vec2(0.0);
    vec2 hi = u_size;
    if (u_bound >= 0.0) {
        // The bound: beyond u_bound of the triangle nothing is drawn. In this slice the
        // triangle is at least dz away, so its rectangle grows by sqrt(bound^2 - dz^2).
        float zmin = min(a.z, min(b.z, c.z));
        float zmax = max(a.z, max(b.z, c.z));
        float dz = max(max(zmin - u_slice, u_slice - zmax), 0.0);
        if (dz > u_bound) {
            // Out of reach: four equal corners outside the view draw nothing.
            gl_Position = vec4(2.0, 2.0, 0.0, 1.0);
            return;
        }
        // One more pixel on every side: the rectangle is conservative, never short.
        float r = sqrt(u_bound * u_bound - dz * dz) + 1.0;
        lo = clamp(min(a.xy, min(b.xy, c.xy)) - r + 0.5, vec2(0.0), u_size);
        hi = clamp(max(a.xy, max(b.xy, c.xy)) + r + 0.5, vec2(0.0), u_size);
    }
    vec2 at = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pixel = mix(lo, hi, at);
    gl_Position = vec4(pixel / u_size * 2.0 - 1.0, 0.0, 1.0);
}
