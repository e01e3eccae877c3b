// Lecture 3, "octrees and quadtrees on the GPU" (reconstructed; src/lecture3/octree/cast.rs):
// the ray cast through the octree.
// Compiled after: glsl/lecture3/pixel_ray.glsl, glsl/lecture3/octree_common.glsl
// Top-down traversal of the occupancy pyramid: an occupied node is entered (one level down,
// the child that holds the ray's current point); an empty node is crossed whole, the ray
// moving to where it leaves the node and one level up, so that empty space costs a step per
// large node instead of one per voxel. An occupied voxel of level 0 is the hit.

void main() {
    Ray r = pixel_ray();
    vec2 box = box_interval(r);
    if (box.x > box.y) {
        write_miss(0);
        return;
    }
    float t = box.x;
    ivec3 cell = clamp(ivec3(floor(r.o + t * r.d)), ivec3(0), ivec3(u_n - 1));
    int level = u_top;
    for (int it = 0; it < u_max_iterations; ++it) {
        ivec3 node = cell >> level;
        ivec3 lo = node << level;
        ivec3 hi = lo + (1 << level);
        if (occupied(node, level)) {
            if (level == 0) {
                write_hit(cell, t, it + 1);
                return;
            }
            level -= 1; // the child holding the current point: `cell` is inside it
            continue;
        }
        // Empty: where the ray leaves the node, and through which side.
        vec3 t_side = vec3(BIG);
        for (int k = 0; k < 3; ++k) {
            if (r.d[k] > 0.0) t_side[k] = (float(hi[k]) - r.o[k]) / r.d[k];
            if (r.d[k] < 0.0) t_side[k] = (float(lo[k]) - r.o[k]) / r.d[k];
        }
        float t_exit = min(min(t_side.x, t_side.y), t_side.z);
        if (t_exit >= box.y) {
            write_miss(it + 1);
            return;
        }
        int axis = t_side.x <= t_side.y && t_side.x <= t_side.z ? 0 : (t_side.y <= t_side.z ? 1 : 2);
        t = t_exit;
        // The neighbouring cell: across the exit side, the other coordinates where the ray is
        // (kept inside the node against rounding).
        ivec3 next = clamp(ivec3(floor(r.o + t * r.d)), lo, hi - 1);
        next[axis] = r.d[axis] > 0.0 ? hi[axis] : lo[axis] - 1;
        if (any(lessThan(next, ivec3(0))) || any(greaterThanEqual(next, ivec3(u_n)))) {
            write_miss(it + 1);
            return;
        }
        cell = next;
        level = min(level + 1, u_top);
    }
    write_unfinished();
}
