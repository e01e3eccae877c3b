#version 330 core
// Lecture 3, "octrees and quadtrees on the GPU" (reconstructed; src/lecture3/octree/cast.rs):
// what the octree and flat ray casts share.
// Compiled after: glsl/lecture3/pixel_ray.glsl
// Each fragment casts its pixel's ray into the N^3 voxel grid (grid space: the cube [0, N]^3,
// the ray parameter the distance along the unit world direction) and writes the first
// occupied voxel it meets, the parameter where it enters it, and its step count.

uniform float u_world_to_grid; // grid units per world unit
uniform int u_n;               // the leaf grid's side
uniform int u_top;             // the root's level
uniform int u_tiles_x[8];      // tiles per row of each level's texture
uniform int u_max_iterations;  // far more than any cast needs; reaching it is reported
uniform sampler2D u_level0;    // the occupancy levels, finest first (unused ones: any texture)
uniform sampler2D u_level1;
uniform sampler2D u_level2;
uniform sampler2D u_level3;
uniform sampler2D u_level4;
uniform sampler2D u_level5;
uniform sampler2D u_level6;
uniform sampler2D u_level7;

layout(location = 0) out vec4 o_hit;   // the voxel (i, j, l) and the entry parameter
layout(location = 1) out vec4 o_stats; // steps, 1 hit / 0 miss / -1 unfinished

Ray pixel_ray() {
    return pixel_ray_scaled(vec3(u_world_to_grid));
}

// The parameter interval inside [0, N]^3 from 0 on; empty (x > y) when the ray misses it.
vec2 box_interval(Ray r) {
    return ray_box(r, vec3(float(u_n)));
}

// Whether node v of `level` is occupied (its z slice tiled as the level's texture lays it).
bool occupied(ivec3 v, int level) {
    int n = u_n >> level;
    int tx = u_tiles_x[level];
    ivec2 p = v.xy + ivec2(v.z % tx, v.z / tx) * n;
    float value;
    // Samplers are not indexable by a variable in GLSL 3.30: one branch per level.
    if (level == 0) value = texelFetch(u_level0, p, 0).r;
    else if (level == 1) value = texelFetch(u_level1, p, 0).r;
    else if (level == 2) value = texelFetch(u_level2, p, 0).r;
    else if (level == 3) value = texelFetch(u_level3, p, 0).r;
    else if (level == 4) value = texelFetch(u_level4, p, 0).r;
    else if (level == 5) value = texelFetch(u_level5, p, 0).r;
    else if (level == 6) value = texelFetch(u_level6, p, 0).r;
    else value = texelFetch(u_level7, p, 0).r;
    return value > 0.0;
}

void write_hit(ivec3 voxel, float t, int steps) {
    o_hit = vec4(vec3(voxel), t);
    o_stats = vec4(float(steps), 1.0, 0.0, 0.0);
}

void write_miss(int steps) {
    o_hit = vec4(0.0, 0.0, 0.0, -1.0);
    o_stats = vec4(float(steps), 0.0, 0.0, 0.0);
}

void write_unfinished() {
    o_hit = vec4(0.0, 0.0, 0.0, -1.0);
    o_stats = vec4(float(u_max_iterations), -1.0, 0.0, 0.0);
}
