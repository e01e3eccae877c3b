#version 330 core
// Compiled after: glsl/lecture1/penetration_ray.glsl
// Lecture 1, penetration depth (Kim, Otaduy, Lin & Manocha, SCA 2002), the closest-point query
// by rasterization (a reconstruction: lecture1-sources.md, section 1): one pass over the back
// faces of every Minkowski sum, for one cube face.
// T is where the pixel's ray from the origin leaves the union of the sums, found pass by
// pass: a sum whose interval on the ray starts at or before the T of the previous pass and
// ends after it extends the covered part of the ray to its exit. MAX blending keeps the
// farthest such exit; a fragment that would not raise T is discarded, so the occlusion query
// around the pass counts exactly the pixels it raised, and a pass that raises none ends the
// query.

// Plane k (normal xyz, unit; offset w; inside: dot(n, x) <= w) at texel
// (k % u_planes_per_row, k / u_planes_per_row).
uniform sampler2D u_planes;
uniform int u_planes_per_row;
// T of the previous pass, the same 6N x N layout as the target.
uniform sampler2D u_previous;
// The face's right, up and forward (columns), its index (columns fN .. fN + N), and N.
uniform mat3 u_face;
uniform int u_face_index;
uniform float u_resolution;

flat in ivec2 v_planes;

out float o_exit;

vec4 sum_plane(int k) {
    return texelFetch(u_planes, ivec2(k % u_planes_per_row, k / u_planes_per_row), 0);
}

void main() {
    // The ray through this pixel's centre, as the CPU reference builds it.
    vec2 local = gl_FragCoord.xy - vec2(float(u_face_index) * u_resolution, 0.0);
    vec2 st = local * (2.0 / u_resolution) - 1.0;
    vec3 direction = normalize(u_face[2] + st.x * u_face[0] + st.y * u_face[1]);

    // This sum's entry and exit along the ray, from its planes.
    vec2 interval = ray_interval(direction, v_planes.x, v_planes.y);

    // Only a sum entered within the covered part of the ray, and left beyond it, raises T.
    float previous = texelFetch(u_previous, ivec2(gl_FragCoord.xy), 0).r;
    if (!(interval.x <= previous && interval.y > previous)) discard;
    o_exit = interval.y;
}
