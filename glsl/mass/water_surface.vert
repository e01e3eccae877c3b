#version 330 core
// The fluid surface of paper 4, section 5.2, one instance per body: the plane
// z = u_water_level over the body's tile, as a quad covering exactly its framing window
// (a height field would displace a grid here; the method only asks that the surface
// normals keep the sign of their z component). Its depth is clamped into the view volume:
// water above the body then peels nothing away, water below it discards everything.

// Per body (row = instance): (tile x, tile y, tile side, 0) in pixels,
// (framing centre xyz, half width), (half depth, 0, 0, 0).
uniform sampler2D u_tiles;
uniform vec2 u_target_size;   // pixels
uniform float u_water_level;  // world z of the surface

// as in glsl/mass/integrands.vert: the surface point (framing-relative) and its n_z
out vec4 p;
out float n_z;

void main()
{
    int body = gl_InstanceID;
    vec4 tile = texelFetch(u_tiles, ivec2(0, body), 0);
    vec4 frame = texelFetch(u_tiles, ivec2(1, body), 0);
    float half_depth = texelFetch(u_tiles, ivec2(2, body), 0).x;
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    p = vec4((corner * 2.0 - 1.0) * frame.w, u_water_level - frame.z, 1.0);
    n_z = 1.0;
    vec2 pixel = tile.xy + corner * tile.z;
    // Framing::projection maps framing-relative z to -z / half_depth (higher is nearer).
    float depth = clamp(-p.z / half_depth, -1.0, 1.0);
    gl_Position = vec4(pixel / u_target_size * 2.0 - 1.0, depth, 1.0);
}
