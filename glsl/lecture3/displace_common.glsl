#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006):
// what both ray tracers share.
// Compiled after: glsl/lecture3/pixel_ray.glsl, glsl/lecture3/displace_normal.glsl
// What the displacement tracers share: the pixel's ray in grid space, the box it enters,
// the bilinear patches of the height map, and the outputs (hit, statistics, shaded colour,
// depth). Grid space: x, y in patches (patch (i, j) spans [i, i+1] x [j, j+1]), z the height
// in [0, 1]; the ray parameter is the distance along the unit world direction.

uniform ivec2 u_patches;       // (width - 1, height - 1)
uniform sampler2D u_heights;   // the height map, one sample per texel
uniform mat4 u_view_projection;

layout(location = 0) out vec4 o_hit;    // grid x, y, z and the ray parameter
layout(location = 1) out vec4 o_stats;  // iterations, kind (1 surface, 2 wall, -1 unfinished)
layout(location = 2) out vec4 o_colour; // shaded
layout(location = 3) out vec4 o_normal; // the normal shaded with (world), xyz

Ray pixel_ray() {
    return pixel_ray_scaled(u_world_to_grid);
}

// The parameter interval inside the box [0, wp] x [0, hp] x [0, 1], from 0 on; empty (x > y)
// when the ray misses it.
vec2 box_interval(Ray r) {
    return ray_box(r, vec3(vec2(u_patches), 1.0));
}

// Whether the ray enters the box through one of its four sides (x or y planes), from outside,
// rather than through its top or bottom (exact.rs). A hit at the entry of such a ray is the
// box's wall; a ray entering through the top where the surface is at the top hits the surface.
bool enters_through_side(Ray r) {
    vec3 hi = vec3(vec2(u_patches), 1.0);
    vec3 near_t = vec3(-BIG);
    for (int k = 0; k < 3; ++k) {
        if (r.d[k] != 0.0) near_t[k] = min((0.0 - r.o[k]) / r.d[k], (hi[k] - r.o[k]) / r.d[k]);
    }
    float side = max(near_t.x, near_t.y);
    return side > 0.0 && side >= near_t.z;
}

// The corner heights of patch `cell`: (h00, h10, h01, h11).
vec4 corners(ivec2 cell) {
    return vec4(texelFetch(u_heights, cell, 0).r,
                texelFetch(u_heights, cell + ivec2(1, 0), 0).r,
                texelFetch(u_heights, cell + ivec2(0, 1), 0).r,
                texelFetch(u_heights, cell + ivec2(1, 1), 0).r);
}

// The bilinear height field at grid point g.
float height_at(vec2 g) {
    ivec2 cell = clamp(ivec2(floor(g)), ivec2(0), u_patches - 1);
    vec2 st = g - vec2(cell);
    vec4 h = corners(cell);
    return mix(mix(h.x, h.y, st.x), mix(h.z, h.w, st.x), st.y);
}

// Where the segment start + u step, u in [0, len], first lies at or below the patch with
// corners h (start in the patch's local frame): f(u) = z(u) - H(s(u), t(u)) = a u^2 + b u + c
// (patch.rs). -1 when it does not.
float patch_first_hit(vec4 h, vec3 start, vec3 step, float len) {
    float A = h.y - h.x;
    float B = h.z - h.x;
    float C = h.x - h.y - h.z + h.w;
    float a = -C * step.x * step.y;
    float b = step.z - A * step.x - B * step.y - C * (start.x * step.y + start.y * step.x);
    float c = start.z - (h.x + A * start.x + B * start.y + C * start.x * start.y);
    if (c <= 0.0) return 0.0;
    float best = BIG;
    float scale = max(abs(a), max(abs(b), abs(c)));
    if (abs(a) <= 1e-6 * scale) {
        if (b != 0.0) {
            float u = -c / b;
            if (u >= 0.0 && u <= len) best = u;
        }
    } else {
        float disc = b * b - 4.0 * a * c;
        if (disc >= 0.0) {
            float q = -0.5 * (b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
            float r1 = q / a;
            float r2 = q != 0.0 ? c / q : r1;
            if (r1 >= 0.0 && r1 <= len) best = min(best, r1);
            if (r2 >= 0.0 && r2 <= len) best = min(best, r2);
        }
    }
    return best < BIG ? best : -1.0;
}

// Writes the hit at parameter tau shown with `surface_n` where it is on the surface: its grid
// position, statistics, a shaded colour (that normal, or the wall's, under one directional
// light, on a checkerboard of 8x8 patches) and its depth. A prefiltered hit's normal is an
// effective one: the light's direction times the mean lit cosine of the facets it stands for,
// so that its shading is their mean shading.
void write_shaded(Ray r, float tau, bool wall, float iterations, vec3 surface_n) {
    vec3 g = r.o + tau * r.d;
    o_hit = vec4(g, tau);
    vec3 n = surface_n;
    if (wall) {
        // The box side the ray came through: the one it is closest to.
        vec2 to_low = g.xy;
        vec2 to_high = vec2(u_patches) - g.xy;
        float m = min(min(to_low.x, to_low.y), min(to_high.x, to_high.y));
        n = m == to_low.x ? vec3(-1, 0, 0) : m == to_high.x ? vec3(1, 0, 0)
          : m == to_low.y ? vec3(0, -1, 0) : vec3(0, 1, 0);
    }
    o_stats = vec4(iterations, wall ? 2.0 : 1.0, 0.0, 0.0);
    o_normal = vec4(n, 0.0);
    ivec2 square = ivec2(floor(g.xy / 8.0));
    vec3 albedo = ((square.x + square.y) & 1) == 0 ? vec3(0.85, 0.75, 0.6) : vec3(0.55, 0.6, 0.75);
    vec3 light = light_direction();
    o_colour = vec4(albedo * (0.25 + 0.75 * max(dot(n, light), 0.0)), 1.0);
    vec4 clip = u_view_projection * vec4(g / u_world_to_grid, 1.0);
    gl_FragDepth = clip.z / clip.w * 0.5 + 0.5;
}

// Writes the hit at parameter tau on the map's own bilinear field (the patch under the hit).
void write_hit(Ray r, float tau, bool wall, float iterations) {
    vec3 g = r.o + tau * r.d;
    ivec2 cell = clamp(ivec2(floor(g.xy)), ivec2(0), u_patches - 1);
    write_shaded(r, tau, wall, iterations, patch_normal(corners(cell), g.xy - vec2(cell), 1.0));
}

// A traversal that ran out of iterations: a bug, reported, never a silent miss.
void write_unfinished(float iterations) {
    o_hit = vec4(0.0, 0.0, 0.0, -1.0);
    o_stats = vec4(iterations, -1.0, 0.0, 0.0);
    o_colour = vec4(1.0, 0.0, 1.0, 1.0);
    o_normal = vec4(0.0);
    gl_FragDepth = 0.0;
}
