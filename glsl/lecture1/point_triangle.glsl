// Lecture 1, distance fields by rasterization (Hoff et al. 1999; DiFi, Sud et al. 2004): the
// exact distance from a point to a triangle, the work of one fragment (a reconstruction: the
// sources rasterize distance meshes; here each fragment computes its distance exactly).
// No #version line: the shaders that name this file give theirs (330 for the slice passes,
// 430 for the compute counterpart). The same steps as src/lecture1/distance_field/
// point_triangle.rs.

// Distance from p to the segment a b (a point when a == b).
float segment_distance(vec3 p, vec3 a, vec3 b) {
    vec3 ab = b - a;
    float len2 = dot(ab, ab);
    float t = len2 > 0.0 ? clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return length(p - (a + t * ab));
}

// Distance from p to the triangle a b c: to its plane when p projects inside it, else to
// the nearest edge. A triangle of zero area is only its edges.
float point_triangle_distance(vec3 p, vec3 a, vec3 b, vec3 c) {
    vec3 n = cross(b - a, c - a);
    float n2 = dot(n, n);
    bool inside = n2 > 0.0
        && dot(cross(b - a, p - a), n) >= 0.0
        && dot(cross(c - b, p - b), n) >= 0.0
        && dot(cross(a - c, p - c), n) >= 0.0;
    if (inside) {
        return abs(dot(p - a, n)) / sqrt(n2);
    }
    return min(segment_distance(p, a, b),
               min(segment_distance(p, b, c), segment_distance(p, c, a)));
}
