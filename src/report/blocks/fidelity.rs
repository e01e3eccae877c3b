//! The GL features behind the building blocks.

use crate::report::Fidelity;

pub fn rows() -> Vec<Fidelity> {
    vec![
        Fidelity::new(
            "ping-pong render-to-texture reduction, 2x2 per pass",
            "paper 4 section 3.3, Fig. 2; paper 1 section 5.3",
            "src/gl/reduce.rs, glsl/gl/reduce.frag",
            "none: 2x2 texels per pass, ceil(log2 n) passes, one texel read back",
        ),
        Fidelity::new(
            "GL timer query (TIME_ELAPSED) for GPU pass time",
            "(measurement)",
            "src/gl/query.rs",
            "the papers timed with their own (unstated) clocks; GPU passes are timed here with \
             timer queries, whole frames with the wall clock",
        ),
    ]
}
