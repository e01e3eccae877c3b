//! The GL features of paper 3, where this code uses them, and what differs.

use crate::report::Fidelity;

pub fn rows() -> Vec<Fidelity> {
    vec![
        Fidelity::new(
            "Matrix product as one rectangle (Moravanszky): each vertex carries the row of W and \
             the column of X, each pixel takes one inner product",
            "Section 3, eq. 2, Fig. 1",
            "glsl/mlp/product.vert, glsl/mlp/product.frag, src/mlp/matmul.rs",
            "the rectangle's corners come from gl_VertexID and a rectangle uniform instead of \
             vertex attributes; by default each pixel loops over all N inputs in one GLSL 330 \
             pass (see the next row for the paper's split)",
        ),
        Fidelity::new(
            "As many product passes as the GPU requires, each adding its inputs to the running \
             sum of the passes before",
            "Section 3 (number of rendering passes)",
            "glsl/mlp/inner_product.frag, glsl/mlp/product_accumulate.frag, src/mlp/matmul.rs",
            "the paper states neither its pass count nor how passes combine: here each pass \
             after the first reads the running sum from the previous pass's target (ping-pong; \
             2004 boards could not blend float targets) and adds its inputs in the same order \
             as one pass; the limit of 15 inputs per pass is our estimate from ps_2_0's 32 \
             texture loads, not the paper's; the split is a choice (--inputs-per-pass), one \
             pass by default, and only in the faithful formulation",
        ),
        Fidelity::new(
            "Bias + sigmoid in one pass, 1D bias texture addressed by the vertical position",
            "Section 3, eq. 3",
            "glsl/mlp/bias_sigmoid.vert, glsl/mlp/bias_sigmoid.frag, src/mlp/activation.rs",
            "none: one pass adding texture W x X and the 1D bias texture, then the sigmoid; an \
             identity activation (for linear output layers, not in the paper) skips the sigmoid",
        ),
        Fidelity::new(
            "Render-target texture of one layer is the next layer's X; nothing read back until \
             the end",
            "Section 3, last paragraph",
            "src/mlp/chain.rs",
            "none: R (L wide, M high) is laid out like X and bound as the next layer's input; \
             the final readback is timed as a step of its own, which Table 1 does not list",
        ),
        Fidelity::new(
            "Input vectors accumulated into one texture, up to the maximum texture size (2048 on \
             the paper's board)",
            "Section 4, footnote 1",
            "src/mlp/textures.rs, src/mlp/tiling.rs",
            "the limit is this renderer's texture and viewport size (2048 only in the row that \
             mimics the paper's board); larger batches are split into tiles of input vectors \
             run one after another, which the paper does not describe; a layer wider than a \
             texture is refused",
        ),
        Fidelity::new(
            "11 x 11 grey window, 30 hidden nodes, output thresholded into text / non-text",
            "Section 4, Fig. 2",
            "src/mlp/window.rs, src/mlp/train.rs, src/mlp/detect.rs",
            "the paper takes grey values 'at predefined positions' in the window without listing \
             them: here all 121, scaled to [0, 1], edge pixels repeated at the border; the \
             threshold (0.5) is not stated in the paper",
        ),
        Fidelity::new(
            "The network's layers: one hidden layer of 30 sigmoid nodes between the 121 inputs \
             and one output",
            "Section 4: 'the number of nodes in each hidden layer set at 30'; the number of \
             hidden layers is not given",
            "src/mlp/train.rs, src/mlp/detect.rs, assets/mlp/text_detector.json",
            "one hidden layer is our choice (the paper's words allow more); the GPU chain runs \
             any number of layers (section 3's layer after layer), so a network file with more \
             runs the same way",
        ),
        Fidelity::new(
            "The paper's board, an ATI RADEON 9700 PRO: 24-bit floats in the fragment pipeline, \
             textures up to 2048, no float blending",
            "Section 4, Table 1, footnote 1",
            "glsl/mlp/fp24.glsl, src/mlp/fp24.rs, src/gl/period.rs (--period, the period tables)",
            "emulated, not the board: every step is computed in fp32 and rounded to a 16-bit \
             mantissa and 7-bit exponent (round to nearest even, no denormals, overflow to \
             infinity; the R300's own rounding mode and edge behaviour are not documented \
             publicly), so a result is fp24(fp32(a op b)) rather than a correctly rounded fp24 \
             op; the board's multiply-add may not have rounded the product before adding; its \
             exp and reciprocal approximations are replaced by fp32 exp and division, rounded; \
             fetched texels are rounded, texture coordinates are not",
        ),
        Fidelity::new(
            "Not in the paper: packed RGBA variant (4 x 4 outputs per fragment, MRT)",
            "-",
            "glsl/mlp/packed_product.frag, src/mlp/packed.rs",
            "an extension: four values per RGBA texel and a 4 x 4 block of outputs per fragment \
             through four render targets; shown beside the faithful passes, never instead of them",
        ),
        Fidelity::new(
            "Differences: the paper's weights and training data are unpublished (trained here on \
             synthetic font8x8 text, or on the user's image + mask pairs)",
            "Section 3-4",
            "src/mlp/synth.rs, src/mlp/labelled.rs, src/mlp/train.rs",
            "the detector is trained here by online backpropagation on synthetic font8x8 pages \
             (the paper refers to its authors' earlier work); the test image is scikit-image's \
             text.png, not the paper's; Table 1's unit and the paper's CPU are not stated, so \
             only ratios measured in one run are compared",
        ),
    ]
}
