//! The network file and the input file: JSON formats, parsing and validation.
//!
//! Network: `{"layers":[{"weights":[[w_11..w_1N], .. [w_M1..w_MN]], "bias":[b_1..b_M],
//! "activation":"sigmoid"|"identity"}, ...]}`; row i of `weights` is the paper's W_i, the
//! weights into output node i. Inputs: `[[x_1..x_N], ...]`, one row per input vector, so row
//! j of the file is column X_j of the paper's X (eq. 1).

use ndarray::{Array1, Array2};
use serde::{Deserialize, Serialize};

/// The non-linear function applied after `W x X + B` (eq. 3 uses the sigmoid).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Activation {
    /// `1 / (1 + e^-m)`, eq. 3.
    Sigmoid,
    /// `m` unchanged (a linear output layer).
    Identity,
}

impl Activation {
    /// The activation of one value, in fp32 as the shaders compute it.
    pub fn apply(self, m: f32) -> f32 {
        match self {
            Activation::Sigmoid => 1.0 / (1.0 + (-m).exp()),
            Activation::Identity => m,
        }
    }

    /// The name used in the network file.
    pub fn name(self) -> &'static str {
        match self {
            Activation::Sigmoid => "sigmoid",
            Activation::Identity => "identity",
        }
    }
}

/// One fully connected layer: `R = activation(W x X + B)` (eq. 2-3).
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// W, M x N: row i holds the weights from the N input nodes into output node i.
    pub weights: Array2<f32>,
    /// b, M values: the bias of each output node.
    pub bias: Array1<f32>,
    pub activation: Activation,
}

impl Layer {
    /// N, the number of input nodes.
    pub fn inputs(&self) -> usize {
        self.weights.ncols()
    }

    /// M, the number of output nodes.
    pub fn outputs(&self) -> usize {
        self.weights.nrows()
    }
}

/// A validated multilayer perceptron: at least one layer, each layer's N equal to the
/// previous layer's M, every weight and bias finite.
#[derive(Clone, Debug, PartialEq)]
pub struct Network {
    layers: Vec<Layer>,
}

/// Everything that can be wrong with a network file or an input file.
#[derive(Debug, thiserror::Error)]
pub enum FormatError {
    #[error("not valid JSON for {what}: {source}")]
    Json {
        what: &'static str,
        source: serde_json::Error,
    },
    #[error(
        "{what} contains `{literal}` (line {line}): JSON has no NaN or infinity, and every \
         weight, bias and input must be a finite number"
    )]
    NonFiniteLiteral {
        what: &'static str,
        literal: &'static str,
        line: usize,
    },
    #[error("the network has no layers (`layers` is empty)")]
    NoLayers,
    #[error("layer {layer}: `weights` is empty; a layer needs at least one row (output node) and one column (input)")]
    EmptyLayer { layer: usize },
    #[error("layer {layer}: `weights` row {row} has {len} values but row 0 has {expected}; every row must have one weight per input (N)")]
    RaggedWeights {
        layer: usize,
        row: usize,
        len: usize,
        expected: usize,
    },
    #[error("layer {layer}: `bias` has {len} values but `weights` has {expected} rows; there is one bias per output node (M)")]
    BiasLength {
        layer: usize,
        len: usize,
        expected: usize,
    },
    #[error("layer {layer} takes {inputs} inputs (columns of `weights`) but layer {previous} has {outputs} outputs (rows of `weights`)")]
    LayerMismatch {
        layer: usize,
        inputs: usize,
        previous: usize,
        outputs: usize,
    },
    #[error("layer {layer}: {what} is not a finite number ({value})")]
    NonFinite {
        layer: usize,
        what: String,
        value: f32,
    },
    #[error("the input file has no input vectors (it must be `[[x_1, .., x_N], ...]`)")]
    NoInputs,
    #[error("input vector {row} has {len} values but the network takes {expected} inputs")]
    InputLength {
        row: usize,
        len: usize,
        expected: usize,
    },
    #[error("input vector {row}, value {col} is not a finite number ({value})")]
    InputNonFinite { row: usize, col: usize, value: f32 },
}

/// The file form of a layer, before validation.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct LayerFile {
    weights: Vec<Vec<f32>>,
    bias: Vec<f32>,
    activation: Activation,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct NetworkFile {
    layers: Vec<LayerFile>,
}

impl Network {
    /// Checks the layers (see [`Network`]) and builds the network.
    pub fn new(layers: Vec<Layer>) -> Result<Network, FormatError> {
        if layers.is_empty() {
            return Err(FormatError::NoLayers);
        }
        for (l, layer) in layers.iter().enumerate() {
            check_layer(l, layer)?;
            if l > 0 && layer.inputs() != layers[l - 1].outputs() {
                return Err(FormatError::LayerMismatch {
                    layer: l,
                    inputs: layer.inputs(),
                    previous: l - 1,
                    outputs: layers[l - 1].outputs(),
                });
            }
        }
        Ok(Network { layers })
    }

    /// Parses and validates a network file's text.
    pub fn from_json(text: &str) -> Result<Network, FormatError> {
        let file: NetworkFile = parse_json(text, "the network file")?;
        let mut layers = Vec::with_capacity(file.layers.len());
        for (l, layer) in file.layers.into_iter().enumerate() {
            let weights = rows_to_matrix(&layer.weights).map_err(|(row, len, expected)| {
                if expected == 0 {
                    FormatError::EmptyLayer { layer: l }
                } else {
                    FormatError::RaggedWeights {
                        layer: l,
                        row,
                        len,
                        expected,
                    }
                }
            })?;
            layers.push(Layer {
                weights,
                bias: Array1::from(layer.bias),
                activation: layer.activation,
            });
        }
        Network::new(layers)
    }

    /// The network file's text; [`Network::from_json`] reads it back bit for bit.
    pub fn to_json(&self) -> String {
        let file = NetworkFile {
            layers: self
                .layers
                .iter()
                .map(|layer| LayerFile {
                    weights: layer.weights.outer_iter().map(|row| row.to_vec()).collect(),
                    bias: layer.bias.to_vec(),
                    activation: layer.activation,
                })
                .collect(),
        };
        serde_json::to_string(&file).expect("a network serialises")
    }

    pub fn layers(&self) -> &[Layer] {
        &self.layers
    }

    /// N of the first layer: the length of one input vector.
    pub fn inputs(&self) -> usize {
        self.layers[0].inputs()
    }

    /// M of the last layer: the length of one output vector.
    pub fn outputs(&self) -> usize {
        self.layers.last().map_or(0, Layer::outputs)
    }

    /// Multiply-adds of one input vector through all layers (2 flops each).
    pub fn flops_per_input(&self) -> f64 {
        self.layers
            .iter()
            .map(|l| 2.0 * (l.inputs() * l.outputs()) as f64)
            .sum()
    }
}

fn check_layer(l: usize, layer: &Layer) -> Result<(), FormatError> {
    if layer.outputs() == 0 || layer.inputs() == 0 {
        return Err(FormatError::EmptyLayer { layer: l });
    }
    if layer.bias.len() != layer.outputs() {
        return Err(FormatError::BiasLength {
            layer: l,
            len: layer.bias.len(),
            expected: layer.outputs(),
        });
    }
    if let Some(((i, j), &value)) = layer.weights.indexed_iter().find(|(_, v)| !v.is_finite()) {
        return Err(FormatError::NonFinite {
            layer: l,
            what: format!("weights[{i}][{j}]"),
            value,
        });
    }
    if let Some((i, &value)) = layer.bias.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(FormatError::NonFinite {
            layer: l,
            what: format!("bias[{i}]"),
            value,
        });
    }
    Ok(())
}

/// Parses the input file's text: L input vectors of `expected` values each, as an L x N
/// matrix whose row j is the paper's column X_j.
pub fn parse_inputs(text: &str, expected: usize) -> Result<Array2<f32>, FormatError> {
    let rows: Vec<Vec<f32>> = parse_json(text, "the input file")?;
    if rows.is_empty() {
        return Err(FormatError::NoInputs);
    }
    if let Some((row, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != expected) {
        return Err(FormatError::InputLength {
            row,
            len: r.len(),
            expected,
        });
    }
    let inputs = rows_to_matrix(&rows).expect("rows checked to have equal length");
    if let Some(((row, col), &value)) = inputs.indexed_iter().find(|(_, v)| !v.is_finite()) {
        return Err(FormatError::InputNonFinite { row, col, value });
    }
    Ok(inputs)
}

/// Rows of equal length as a matrix; on a ragged row: (row, its length, row 0's length).
fn rows_to_matrix(rows: &[Vec<f32>]) -> Result<Array2<f32>, (usize, usize, usize)> {
    let cols = rows.first().map_or(0, Vec::len);
    if cols == 0 {
        return Err((0, 0, 0));
    }
    if let Some((row, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != cols) {
        return Err((row, r.len(), cols));
    }
    let flat: Vec<f32> = rows.iter().flatten().copied().collect();
    Ok(Array2::from_shape_vec((rows.len(), cols), flat).expect("shape matches"))
}

/// serde_json, with a clear word for the NaN / Infinity that people write into JSON.
fn parse_json<T: serde::de::DeserializeOwned>(
    text: &str,
    what: &'static str,
) -> Result<T, FormatError> {
    serde_json::from_str(text).map_err(|source| {
        let line = source.line();
        let line_text = text.lines().nth(line.saturating_sub(1)).unwrap_or("");
        let literal = ["NaN", "Infinity", "inf", "nan"]
            .into_iter()
            .find(|lit| line_text.contains(lit));
        match literal {
            Some(literal) if source.is_syntax() => FormatError::NonFiniteLiteral {
                what,
                literal,
                line,
            },
            _ => FormatError::Json { what, source },
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_LAYERS: &str = r#"{"layers":[
        {"weights":[[1,2,3],[4,5,6]],"bias":[0.5,-0.5],"activation":"sigmoid"},
        {"weights":[[1,-1]],"bias":[0],"activation":"identity"}]}"#;

    #[test]
    fn reads_a_two_layer_network() {
        let net = Network::from_json(TWO_LAYERS).unwrap();
        assert_eq!(net.layers().len(), 2);
        assert_eq!((net.inputs(), net.outputs()), (3, 1));
        assert_eq!(net.layers()[0].weights[[1, 2]], 6.0);
        assert_eq!(net.layers()[1].activation, Activation::Identity);
        assert_eq!(net.flops_per_input(), 2.0 * (6.0 + 2.0));
    }

    #[test]
    fn json_round_trip_is_exact() {
        let net = Network::from_json(TWO_LAYERS).unwrap();
        let mut layers = net.layers().to_vec();
        layers[0].weights[[0, 0]] = 0.1f32.powi(7) * std::f32::consts::PI;
        let net = Network::new(layers).unwrap();
        assert_eq!(Network::from_json(&net.to_json()).unwrap(), net);
    }

    fn error_of(text: &str) -> String {
        Network::from_json(text).unwrap_err().to_string()
    }

    #[test]
    fn ragged_rows_are_named() {
        let e =
            error_of(r#"{"layers":[{"weights":[[1,2],[3]],"bias":[0,0],"activation":"sigmoid"}]}"#);
        assert!(
            e.contains("layer 0") && e.contains("row 1 has 1 values"),
            "{e}"
        );
    }

    #[test]
    fn layer_size_mismatch_is_named() {
        let e = error_of(
            r#"{"layers":[{"weights":[[1,2],[3,4]],"bias":[0,0],"activation":"sigmoid"},
                          {"weights":[[1,2,3]],"bias":[0],"activation":"sigmoid"}]}"#,
        );
        assert!(
            e.contains("layer 1 takes 3 inputs") && e.contains("2 outputs"),
            "{e}"
        );
    }

    #[test]
    fn bias_length_is_checked() {
        let e = error_of(r#"{"layers":[{"weights":[[1,2]],"bias":[0,0],"activation":"sigmoid"}]}"#);
        assert!(e.contains("`bias` has 2 values"), "{e}");
    }

    #[test]
    fn unknown_activation_lists_the_known_ones() {
        let e = error_of(r#"{"layers":[{"weights":[[1]],"bias":[0],"activation":"relu"}]}"#);
        assert!(
            e.contains("relu") && e.contains("sigmoid") && e.contains("identity"),
            "{e}"
        );
    }

    #[test]
    fn nan_literal_and_overflow_are_refused() {
        let e = error_of(r#"{"layers":[{"weights":[[NaN]],"bias":[0],"activation":"sigmoid"}]}"#);
        assert!(e.contains("NaN") && e.contains("finite"), "{e}");
        let e = error_of(r#"{"layers":[{"weights":[[1e39]],"bias":[0],"activation":"sigmoid"}]}"#);
        assert!(e.contains("weights[0][0] is not a finite number"), "{e}");
    }

    #[test]
    fn empty_networks_and_layers_are_refused() {
        assert!(error_of(r#"{"layers":[]}"#).contains("no layers"));
        let e = error_of(r#"{"layers":[{"weights":[],"bias":[],"activation":"sigmoid"}]}"#);
        assert!(e.contains("`weights` is empty"), "{e}");
        assert!(error_of(r#"{"layer":[]}"#).contains("not valid JSON"));
    }

    #[test]
    fn inputs_are_checked_against_the_network() {
        let x = parse_inputs("[[1,2,3],[4,5,6]]", 3).unwrap();
        assert_eq!(x.dim(), (2, 3));
        assert_eq!(x[[1, 0]], 4.0);
        let e = parse_inputs("[[1,2,3],[4,5]]", 3).unwrap_err().to_string();
        assert!(e.contains("input vector 1 has 2 values"), "{e}");
        assert!(parse_inputs("[]", 3)
            .unwrap_err()
            .to_string()
            .contains("no input"));
        assert!(parse_inputs("[[1e40,0,0]]", 3).is_err());
    }
}
