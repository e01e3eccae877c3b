// The last of the n + 2 passes [paper 4, section 5.2, Fig. 8]: the fluid surface inside
// the body, drawn only where the first peel below the surface faced down (the body is
// there at the water line). Compiled after cg_ports/mass_integrands.frag.
#undef main

// o_faces_down of pass 1.
uniform sampler2D u_first_peel_faces_down;

void main()
{
    if (texelFetch(u_first_peel_faces_down, ivec2(gl_FragCoord.xy), 0).r < 0.5) discard;
    integrands();
}
