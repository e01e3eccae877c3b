#version 330 core
// Lecture 1, generalized Voronoi diagrams (Hoff et al. 1999, a reconstruction): the exact
// distance from this pixel's centre to one site, written as the fragment's depth, so that the
// depth test (LESS, sites in id order) keeps the nearest site; the colour keeps its id and
// distance. Coordinates are pixels from the domain's corner.

uniform sampler2D u_sites;   // site i: texels (2 (i % u_per_row) + k, i / u_per_row), k = 0, 1
uniform int u_per_row;
uniform float u_depth_scale; // 1 / (the depth range in pixels)
uniform float u_pixel;       // input units per pixel
flat in int v_site;
out vec4 o_site;             // site id, distance (input units)

// Distance from p to the segment a b (a point when a == b).
float segment_distance(vec2 p, vec2 a, vec2 b) {
    vec2 ab = b - a;
    float len2 = dot(ab, ab);
    float t = len2 > 0.0 ? clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return length(p - (a + t * ab));
}

float cross2(vec2 u, vec2 v) { return u.x * v.y - u.y * v.x; }

// Inside the triangle or on its edges (either orientation; never for zero area).
bool inside_triangle(vec2 p, vec2 a, vec2 b, vec2 c) {
    float area = cross2(b - a, c - a);
    if (area == 0.0) return false;
    float s = sign(area);
    return s * cross2(b - a, p - a) >= 0.0 && s * cross2(c - b, p - b) >= 0.0
        && s * cross2(a - c, p - c) >= 0.0;
}

void main() {
    // The site: corners a, b, c and its kind (0 point, 1 segment, 2 triangle).
    ivec2 at = ivec2(2 * (v_site % u_per_row), v_site / u_per_row);
    vec4 t0 = texelFetch(u_sites, at, 0);
    vec4 t1 = texelFetch(u_sites, at + ivec2(1, 0), 0);
    vec2 a = t0.xy, b = t0.zw, c = t1.xy;
    int kind = int(t1.z);
    vec2 p = gl_FragCoord.xy;
    // Its exact distance.
    float d;
    if (kind == 0) {
        d = length(p - a);
    } else if (kind == 1) {
        d = segment_distance(p, a, b);
    } else if (inside_triangle(p, a, b, c)) {
        d = 0.0;
    } else {
        d = min(segment_distance(p, a, b),
                min(segment_distance(p, b, c), segment_distance(p, c, a)));
    }
    // The depth test chooses the nearest site.
    gl_FragDepth = d * u_depth_scale;
    o_site = vec4(float(v_site), d * u_pixel, 0.0, 1.0);
}
