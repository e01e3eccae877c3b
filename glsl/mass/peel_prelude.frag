// Prelude of the integrand passes of paper 4: compiled before the section 3.1 listing
// (cg_ports/mass_integrands.frag), whose main() the macro renames to integrands() so that
// the peel test of section 3.2 and the water tests of section 5.2 can run first.
#define main integrands
