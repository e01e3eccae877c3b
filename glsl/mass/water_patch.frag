// The last of the n + 2 passes [paper 4, section 5.2, Fig. 8]: the fluid surface inside
// the body, drawn only where the first peel below the surface faced down (the body is
// there at the water line). That test is the stencil bit pass 1 wrote (the pass draws
// with the stencil test EQUAL 1). Compiled after cg_ports/mass_integrands.frag.
// Compiled after: glsl/mass/peel_prelude.frag, cg_ports/mass_integrands.frag
#undef main

void main()
{
    integrands();
}
