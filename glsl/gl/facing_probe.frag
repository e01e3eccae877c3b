#version 330 core
// Building block: the facing probe (src/gl/facing.rs). Writes what gl_FrontFacing says of
// the fragment's triangle: 1 for front, 0.5 for back (0 stays "no fragment").

out vec4 o_facing;

void main() {
    o_facing = vec4(gl_FrontFacing ? 1.0 : 0.5, 0.0, 0.0, 1.0);
}
