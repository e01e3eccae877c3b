// Lecture 3, "octrees and quadtrees on the GPU" (reconstructed; src/lecture3/octree/cast.rs):
// the flat search the octree is measured against.
// Compiled after: glsl/lecture3/pixel_ray.glsl, glsl/lecture3/octree_common.glsl
// A 3D DDA over the full grid (Amanatides & Woo): the ray visits every voxel it crosses, in
// order, and stops at the first occupied one. Empty space costs one step per voxel.

void main() {
    Ray r = pixel_ray();
    vec2 box = box_interval(r);
    if (box.x > box.y) {
        write_miss(0);
        return;
    }
    float t = box.x;
    ivec3 cell = clamp(ivec3(floor(r.o + t * r.d)), ivec3(0), ivec3(u_n - 1));
    for (int it = 0; it < u_max_iterations; ++it) {
        if (occupied(cell, 0)) {
            write_hit(cell, t, it + 1);
            return;
        }
        // Where the ray leaves this voxel, and through which side.
        vec3 t_side = vec3(BIG);
        for (int k = 0; k < 3; ++k) {
            if (r.d[k] > 0.0) t_side[k] = (float(cell[k] + 1) - r.o[k]) / r.d[k];
            if (r.d[k] < 0.0) t_side[k] = (float(cell[k]) - r.o[k]) / r.d[k];
        }
        float t_exit = min(min(t_side.x, t_side.y), t_side.z);
        if (t_exit >= box.y) {
            write_miss(it + 1);
            return;
        }
        int axis = t_side.x <= t_side.y && t_side.x <= t_side.z ? 0 : (t_side.y <= t_side.z ? 1 : 2);
        t = t_exit;
        cell[axis] += r.d[axis] > 0.0 ? 1 : -1;
        if (cell[axis] < 0 || cell[axis] >= u_n) {
            write_miss(it + 1);
            return;
        }
    }
    write_unfinished();
}
