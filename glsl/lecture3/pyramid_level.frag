#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006): the
// image pyramid, one level from the level below.
// One level of an image pyramid from the level below: each node keeps the extreme (max or
// min) of its four children, or their mean. The texture's readable levels are narrowed to the
// level below, so texelFetch level 0 reads it. A side that is already 1 repeats its one child
// (counted once by the mean). Every channel is combined alike (a one-channel texture reads
// its value in .r and stores only .r), so a pyramid may carry a vector per node.

uniform sampler2D u_below;
uniform ivec2 u_below_size;
uniform int u_op;            // 0: max, 1: min, 2: mean
uniform ivec2 u_image;       // the image's size before padding (pixels)
uniform ivec2 u_below_span;  // image pixels per node of the level below, along x and y

out vec4 o_value;

// Image pixels that child `c` of the level below covers along one axis.
vec2 covered(ivec2 c) {
    return vec2(clamp(u_image - c * u_below_span, ivec2(0), u_below_span));
}

// region: pyramid-level
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) * 2;
    ivec2 q = min(p + 1, u_below_size - 1);
    vec4 a = texelFetch(u_below, p, 0);
    vec4 b = texelFetch(u_below, ivec2(q.x, p.y), 0);
    vec4 c = texelFetch(u_below, ivec2(p.x, q.y), 0);
    vec4 d = texelFetch(u_below, q, 0);
    if (u_op == 0) {
        o_value = max(max(a, b), max(c, d));
    } else if (u_op == 1) {
        o_value = min(min(a, b), min(c, d));
    } else {
        // The mean of the image pixels under the node: the children's means weighted by how
        // many pixels each covers (padding covers none; a repeated child counts once).
        vec2 wp = covered(p);
        vec2 wq = covered(q) * vec2(notEqual(q, p));
        vec4 w = vec4(wp.x * wp.y, wq.x * wp.y, wp.x * wq.y, wq.x * wq.y);
        float total = w.x + w.y + w.z + w.w;
        o_value = total > 0.0 ? (w.x * a + w.y * b + w.z * c + w.w * d) / total : vec4(0.0);
    }
}
// endregion
