#version 330 core
// The fluid surface of paper 4, section 5.2, over one body's tile: the plane z = level as a
// quad a little larger than the framing window (a height field would displace a grid here;
// the method only asks that the surface normals keep the sign of their z component).
// Its depth is clamped into the view volume: water above the body then peels nothing
// away, water below it discards everything.

uniform vec3 frame_center;  // world point at the framing centre
uniform mat4 projection;    // framing-relative -> clip (Framing::projection)
uniform float half_width;   // of the framing window
uniform float water_level;  // world z of the surface

// as in glsl/mass/integrands.vert: the surface point and the z of its normal
out vec4 p;
out float n_z;

void main()
{
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    p = vec4(corner * half_width * 1.01, water_level - frame_center.z, 1.0);
    n_z = 1.0;
    gl_Position = projection * p;
    gl_Position.z = clamp(gl_Position.z, -gl_Position.w, gl_Position.w);
}
