// Paper 4, section 3.2, on its own GPU: the peel pass of glsl/mass/peel_main.frag with the
// peel test done at the 24 bits of the GeForce 7800 GTX's depth buffer
// (glsl/mass/peel_depth24.glsl in place of the GL layer's float snippet). The stage is the
// files below, in order; this file adds no code (src/mass/peel_depth.rs assembles it).
// Compiled after: glsl/mass/peel_prelude.frag, cg_ports/mass_integrands.frag, glsl/mass/peel_depth24.glsl, glsl/mass/peel_main.frag
