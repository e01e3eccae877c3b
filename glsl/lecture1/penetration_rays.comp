#version 430 core
// Compiled after: glsl/lecture1/penetration_ray.glsl
// Lecture 1, penetration depth (Kim, Otaduy, Lin & Manocha, SCA 2002), the closest-point query
// as a compute pass (then and now; a reconstruction: lecture1-sources.md, section 1).
// One invocation per pixel ray of the same 6N x N cube layout as the classic passes: where
// those rasterize back faces and ping-pong T through passes until an occlusion query counts
// nothing, this walks every sum along its own ray in a loop until no sum raises T. Same
// rays, same intervals (penetration_ray.glsl), same rule; no rasterization, no passes.

layout(local_size_x = 64) in;

// Plane k: normal xyz (unit), offset w; inside: dot(n, x) <= w.
layout(std430, binding = 0) readonly buffer Planes { vec4 b_planes[]; };
// Sum s's planes: first index and count.
layout(std430, binding = 1) readonly buffer Sums { ivec2 b_sums[]; };
// T of every pixel, row-major from the bottom row of the 6N x N layout.
layout(std430, binding = 2) writeonly buffer Exits { float b_exits[]; };

uniform int u_sums;
uniform int u_resolution;
// Exits nearer than the classic views' near plane are not seen there; nor here.
uniform float u_near;
// The first pixel of this dispatch (large layouts take several).
uniform uint u_first;
// Per face: right, up, forward (xyz).
uniform vec4 u_right[6];
uniform vec4 u_up[6];
uniform vec4 u_forward[6];

vec4 sum_plane(int k) {
    return b_planes[k];
}

void main() {
    uint pixel = u_first + gl_GlobalInvocationID.x;
    int width = 6 * u_resolution;
    if (pixel >= uint(width * u_resolution)) return;
    int x = int(pixel) % width;
    int y = int(pixel) / width;
    int face = x / u_resolution;

    // The ray through the pixel's centre, as the classic fragment stage builds it.
    vec2 st = (vec2(x - face * u_resolution, y) + 0.5) * (2.0 / float(u_resolution)) - 1.0;
    vec3 direction = normalize(u_forward[face].xyz + st.x * u_right[face].xyz + st.y * u_up[face].xyz);

    // Raise T by every sum entered within the covered part of the ray, until none does
    // (each sum raises it at most once, so at most u_sums rounds).
    float t = 0.0;
    for (int round = 0; round <= u_sums; ++round) {
        bool raised = false;
        for (int s = 0; s < u_sums; ++s) {
            vec2 interval = ray_interval(direction, b_sums[s].x, b_sums[s].y);
            if (interval.y > u_near && interval.x <= interval.y && interval.x <= t &&
                interval.y > t) {
                t = interval.y;
                raised = true;
            }
        }
        if (!raised) break;
    }
    b_exits[pixel] = t;
}
