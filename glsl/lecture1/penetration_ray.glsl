// Lecture 1, penetration depth (Kim, Otaduy, Lin & Manocha, SCA 2002), a reconstruction: the
// interval of one convex Minkowski sum on a ray from the origin, from its face planes. Shared
// by the fragment pass (penetration_exit.frag) and the compute counterpart
// (penetration_rays.comp), which come after it and define sum_plane(k), the plane k as
// (normal, offset). No #version line.

vec4 sum_plane(int k);

// (entry, exit) of the ray t * direction (t in units of the unit-length direction) through
// the sum whose planes are first .. first + count - 1. A plane n·x <= c bounds t from above
// when the ray runs towards it (n·d > 0) and from below when it runs away from it; a ray
// parallel to a plane it lies outside of misses the sum (entry > exit).
vec2 ray_interval(vec3 direction, int first, int count) {
    float entry = -3.402823e38;
    float exit = 3.402823e38;
    for (int k = first; k < first + count; ++k) {
        vec4 plane = sum_plane(k);
        float along = dot(plane.xyz, direction);
        if (along > 0.0) {
            exit = min(exit, plane.w / along);
        } else if (along < 0.0) {
            entry = max(entry, plane.w / along);
        } else if (plane.w < 0.0) {
            entry = 3.402823e38;
        }
    }
    return vec2(entry, exit);
}
