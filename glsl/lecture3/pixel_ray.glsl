#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" and "octrees and quadtrees on
// the GPU": the pixel's ray and the box it crosses, shared by the displacement tracers and the
// octree casts (uniforms set by Camera::set_ray_uniforms, src/lecture3/displacement/camera.rs).
// Grid space is the world scaled per axis; the ray parameter stays the distance along the unit
// world direction.

uniform vec2 u_viewport;       // image size in pixels
uniform vec3 u_eye;            // world
uniform vec3 u_forward;        // the camera's ray frame (displacement/camera.rs)
uniform vec3 u_right;
uniform vec3 u_up;

const float BIG = 1e30;

struct Ray {
    vec3 o; // grid space
    vec3 d; // grid-space image of the unit world direction
};

// The ray through the centre of this fragment's pixel, in the grid space `world_to_grid`
// (a diagonal scale) makes of the world.
Ray pixel_ray_scaled(vec3 world_to_grid) {
    vec2 ndc = gl_FragCoord.xy / u_viewport * 2.0 - 1.0;
    vec3 dir = normalize(u_forward + ndc.x * u_right + ndc.y * u_up);
    return Ray(u_eye * world_to_grid, dir * world_to_grid);
}

// The parameter interval inside the box [0, hi.x] x [0, hi.y] x [0, hi.z], from 0 on; empty
// (x > y) when the ray misses it.
vec2 ray_box(Ray r, vec3 hi) {
    float t0 = 0.0;
    float t1 = BIG;
    for (int k = 0; k < 3; ++k) {
        if (r.d[k] == 0.0) {
            if (r.o[k] < 0.0 || r.o[k] > hi[k]) return vec2(1.0, 0.0);
            continue;
        }
        float a = (0.0 - r.o[k]) / r.d[k];
        float b = (hi[k] - r.o[k]) / r.d[k];
        t0 = max(t0, min(a, b));
        t1 = min(t1, max(a, b));
    }
    return vec2(t0, t1);
}
