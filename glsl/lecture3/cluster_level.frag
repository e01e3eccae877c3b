#version 330 core
// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): building the hierarchy, one level by clustering four nodes.
// One level of the light hierarchy from the level below: each node clusters its four
// children. Flux and VPL count add; position and normal are the children's averages weighted
// by flux (the normal is left unnormalised: its length shrinks as the children disagree);
// the radius bounds every VPL of the cluster: max over children of (distance to the new
// centre + the child's radius). Children without flux take no part. The textures' readable
// levels are narrowed to the level below, so texelFetch level 0 reads it.

uniform sampler2D u_position; // xyz, radius
uniform sampler2D u_normal;   // xyz, weight
uniform sampler2D u_flux;     // rgb, count

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_flux;

void main() {
    ivec2 base = ivec2(gl_FragCoord.xy) * 2;
    ivec2 child[4] = ivec2[4](base, base + ivec2(1, 0), base + ivec2(0, 1), base + ivec2(1, 1));
    vec4 p[4];
    vec4 n[4];
    vec4 f = vec4(0.0);
    float w = 0.0;
    vec3 centre = vec3(0.0);
    vec3 normal = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        p[i] = texelFetch(u_position, child[i], 0);
        n[i] = texelFetch(u_normal, child[i], 0);
        f += texelFetch(u_flux, child[i], 0);
        w += n[i].w;
        centre += n[i].w * p[i].xyz;
        normal += n[i].w * n[i].xyz;
    }
    float radius = 0.0;
    if (w > 0.0) {
        centre /= w;
        normal /= w;
        for (int i = 0; i < 4; ++i) {
            if (n[i].w > 0.0) radius = max(radius, distance(p[i].xyz, centre) + p[i].w);
        }
    }
    o_position = vec4(centre, radius);
    o_normal = vec4(normal, w);
    o_flux = f;
}
