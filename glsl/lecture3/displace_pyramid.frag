// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006): the
// ray traced through the max pyramid.
// Compiled after: glsl/lecture3/pixel_ray.glsl, glsl/lecture3/displace_normal.glsl
// Compiled after: glsl/lecture3/displace_common.glsl
// Compiled after: glsl/lecture3/displace_prefilter.glsl
// Pyramidal displacement mapping [Oh, Ki & Lee, VRST 2006; reconstructed from the
// abstract]: the pixel's ray is traced through the max pyramid of the patch bounds, top
// down. A node whose highest point the ray stays above while it crosses the node is skipped
// whole; otherwise the ray advances to where it reaches the node's bound (never past a
// surface) and descends. At level 0 the ray is intersected with the node's bilinear patch.
// After leaving a node the traversal climbs one level, so empty space is crossed in large
// steps. With the prefilter on (displace_prefilter.glsl) the descent stops at the level of
// the pixel's footprint and meets that level's prefiltered patch instead. (The fragment stage
// is pixel_ray.glsl, displace_normal.glsl, displace_common.glsl, displace_prefilter.glsl, then this file.)

uniform int u_top;            // the top level (one node)
uniform int u_max_iterations; // far more than any traversal needs; reaching it is reported

void main() {
    Ray r = pixel_ray();
    vec2 box = box_interval(r);
    if (box.x > box.y) discard;
    float t = box.x;
    float t_out = box.y;
    vec3 entry = r.o + t * r.d;
    ivec2 cell = clamp(ivec2(floor(entry.xy)), ivec2(0), u_patches - 1);
    int level = u_top;
    int stop = stop_level(box.x, u_top); // 0 without the prefilter
    bool in_entry_cell = true;
    for (int it = 0; it < u_max_iterations; ++it) {
        ivec2 node = cell >> level;
        ivec2 first_cell = node << level;
        ivec2 last_cell = min(((node + 1) << level) - 1, u_patches - 1);
        // Where the ray leaves the node (or the box).
        vec2 t_side = vec2(BIG);
        for (int k = 0; k < 2; ++k) {
            if (r.d[k] > 0.0) t_side[k] = (float(last_cell[k] + 1) - r.o[k]) / r.d[k];
            if (r.d[k] < 0.0) t_side[k] = (float(first_cell[k]) - r.o[k]) / r.d[k];
        }
        float t_exit = min(min(t_side.x, t_side.y), t_out);
        ivec2 at_level = ivec2(u_level_x[level], u_level_y[level]);
        float bound = texelFetch(u_bounds, at_level + node, 0).r;
        bool skip = false;
        if (r.o.z + t * r.d.z > bound) {
            // The ray is above the node's highest point: where does it come down to it?
            float t_plane = r.d.z < 0.0 ? (bound - r.o.z) / r.d.z : BIG;
            if (t_plane >= t_exit) {
                skip = true; // above the bound all the way across: nothing here
            } else {
                // Advance to the bound, still inside this node (clamped against rounding),
                // and never back along the ray: rounding can put the bound's crossing a hair
                // before t, or its cell behind the current one, and going back to a cell the
                // ray has left would loop (seen on an NVIDIA GPU).
                t = max(t, t_plane);
                ivec2 at = ivec2(floor(r.o.xy + t * r.d.xy));
                ivec2 moved = clamp(at, first_cell, last_cell);
                for (int k = 0; k < 2; ++k) {
                    if (r.d[k] > 0.0) moved[k] = max(moved[k], cell[k]);
                    if (r.d[k] < 0.0) moved[k] = min(moved[k], cell[k]);
                }
                in_entry_cell = in_entry_cell && moved == cell;
                cell = moved;
            }
        }
        if (!skip && level == stop) {
            // The finest level (or the prefilter's): the ray against this node's bilinear
            // patch, the map's own at level 0, the prefiltered one above.
            float side = float(1 << level);
            vec2 origin = vec2(node << level);
            vec4 h = level == 0 ? corners(cell) : prefiltered_corners(node, level, bound);
            vec3 q = r.o + t * r.d;
            float u = patch_first_hit(h, vec3((q.xy - origin) / side, q.z),
                                      vec3(r.d.xy / side, r.d.z), max(t_exit - t, 0.0));
            if (u >= 0.0) {
                // A wall only where the ray is under the surface where it enters the box
                // through a side: not where it was moved down to a node's bound plane and a
                // flat patch at that very height starts there (u = 0 as well).
                bool wall = in_entry_cell && t == box.x && u == 0.0 && enters_through_side(r);
                if (level == 0) {
                    write_hit(r, t + u, wall, float(it + 1));
                } else {
                    vec2 g = r.o.xy + (t + u) * r.d.xy;
                    write_shaded(r, t + u, wall, float(it + 1), prefiltered_normal(g, level));
                }
                return;
            }
            skip = true;
        }
        if (!skip) {
            level -= 1;
            continue;
        }
        // Leave the node through the side it exits by, into the neighbouring cell.
        if (t_exit >= t_out) discard; // out of the box: a miss
        t = t_exit;
        int axis = t_side.x <= t_side.y ? 0 : 1;
        int other = 1 - axis;
        ivec2 next;
        next[axis] = r.d[axis] > 0.0 ? last_cell[axis] + 1 : first_cell[axis] - 1;
        next[other] = clamp(int(floor(r.o[other] + t * r.d[other])), first_cell[other],
                            last_cell[other]);
        if (any(lessThan(next, ivec2(0))) || any(greaterThanEqual(next, u_patches))) discard;
        cell = next;
        in_entry_cell = false;
        level = min(level + 1, u_top);
    }
    write_unfinished(float(u_max_iterations));
}
