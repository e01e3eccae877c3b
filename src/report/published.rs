//! The papers' published tables, transcribed in `assets/paper_tables.toml`, as typed structs.
//!
//! The file is deserialised once ([`Published::get`]). Every struct denies unknown keys, so a
//! misspelt, missing or mistyped cell is a load error naming the key and its line, caught by a
//! test, instead of a "-" or a NaN in the report.

use serde::Deserialize;
use std::sync::OnceLock;

/// The TOML text, compiled into the binary.
pub const PAPER_TABLES_TOML: &str = include_str!("../../assets/paper_tables.toml");

/// Every paper's published numbers.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Published {
    pub paper1: Paper1,
    pub paper2: Paper2,
    pub paper3: Paper3,
    pub paper4: Paper4,
}

impl Published {
    /// Parse a transcription; the error names the key (and line) that is wrong.
    pub fn parse(text: &str) -> Result<Published, String> {
        toml::from_str(text).map_err(|e| format!("assets/paper_tables.toml: {e}"))
    }

    /// The shipped transcription, parsed on first use.
    pub fn get() -> anyhow::Result<&'static Published> {
        static PUBLISHED: OnceLock<Result<Published, String>> = OnceLock::new();
        PUBLISHED
            .get_or_init(|| Published::parse(PAPER_TABLES_TOML))
            .as_ref()
            .map_err(|e| anyhow::anyhow!("{e}"))
    }
}

/// Zhang & Kim 2007 (streaming AABBs).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper1 {
    pub source: String,
    pub hardware: String,
    /// Table III, one row per scene in the paper's order.
    pub table3: Vec<Paper1Table3Row>,
    pub table4_setup: Paper1Table4Setup,
    /// Table IV (CULLIDE), one row per scene in the paper's order.
    pub table4: Vec<Paper1Table4Row>,
    pub readback: Paper1Readback,
    pub claims: Paper1Claims,
}

/// One scene of Table III (times in ms).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper1Table3Row {
    pub scene: u32,
    pub models: String,
    pub tris_each: u32,
    pub caps: u32,
    pub pctps: u32,
    pub ctps: u32,
    pub overlap: f64,
    pub readback_encode: f64,
    pub readback_decode: f64,
    pub tri_test: f64,
    pub texture_download: f64,
    pub stream_update: f64,
    pub total: f64,
    /// (min, max) frames per second quoted in Sec. 7.3 / Fig. 8-9.
    pub fps: [f64; 2],
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper1Table4Setup {
    pub resolution: u32,
}

/// One scene of Table IV (CULLIDE; times in ms, missing in percent).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper1Table4Row {
    pub scene: u32,
    pub pruning: f64,
    pub tri_test: f64,
    pub pctps: u32,
    pub ctps: u32,
    pub missing_percent: f64,
}

/// Sec. 5.3 and Fig. 7.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper1Readback {
    pub eta_threshold_percent: f64,
    pub p0_size: u32,
    pub max_readback_ms_2048: f64,
    pub hierarchy_levels: u32,
    pub reduced_block: u32,
    pub geforce6800_full_2048_ms: f64,
    pub geforce6800_full_512_ms: f64,
}

/// Sec. 7.4's comparative claims.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper1Claims {
    pub speedup_over_solid_with_download: [f64; 2],
    pub speedup_over_solid_without_download: [f64; 2],
    pub speedup_over_cullide: f64,
    pub cullide_missing_percent: [f64; 2],
    pub streaming_missing_percent: f64,
}

/// Kang & Han 2006 (crowd skinning).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper2 {
    pub source: String,
    pub hardware: String,
    /// Polygons of the three LOD meshes (section 3).
    pub lod_polygons: [u32; 3],
    pub table1: Paper2Table1,
    /// Fig. 3-5: average frame rates of the snapshot scenes.
    pub runs: Vec<Paper2Run>,
}

/// Table 1: frames per second against the number of characters.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper2Table1 {
    pub caption: String,
    pub characters: Vec<usize>,
    pub soldier_vs: Vec<f64>,
    pub soldier_two_pass: Vec<f64>,
    pub horse_vs: Vec<f64>,
    pub horse_two_pass: Vec<f64>,
}

/// One of Fig. 3-5's runs.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper2Run {
    pub figure: String,
    /// `soldier` or `horse`.
    pub model: String,
    pub characters: usize,
    pub lod_and_culling: bool,
    pub fps: f64,
}

/// Oh & Jung 2004 (neural networks).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper3 {
    pub source: String,
    pub table1: Paper3Table1,
}

/// Table 1: processing times per elementary operation (unit not stated in the paper).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper3Table1 {
    pub caption: String,
    pub hardware: String,
    pub unit: String,
    pub network: String,
    pub max_vectors_per_texture: usize,
    pub gpu_texture_creation: f64,
    pub gpu_matrix_multiplication: f64,
    pub gpu_sigmoid: f64,
    pub cpu_matrix_multiplication: f64,
    pub speedup_claimed: f64,
}

/// Kim, Kim, Ko & Terzopoulos 2006 (mass properties, buoyancy).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper4 {
    pub source: String,
    pub hardware: String,
    /// Table 1: the test objects.
    pub table1: Vec<Paper4Object>,
    pub fig4: Paper4Fig4,
    pub fig5: Paper4Fig5,
    pub buoyancy: Paper4Buoyancy,
}

impl Paper4 {
    /// Table 1's row for `object`, if the paper has it.
    pub fn object(&self, object: &str) -> Option<&Paper4Object> {
        self.table1.iter().find(|o| o.object == object)
    }
}

/// One object of Table 1.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper4Object {
    pub object: String,
    pub vertices: u32,
    pub faces: u32,
    pub peels: u32,
}

/// Fig. 4: only its stated bound survives in the text.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper4Fig4 {
    pub resolutions: Vec<u32>,
    pub bound_resolution: u32,
    pub bound_relative_error: f64,
    pub claim: String,
}

/// Fig. 5: the stated findings.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper4Fig5 {
    pub resolutions: Vec<u32>,
    pub claim_64: String,
    pub claim_128: String,
}

/// Section 5.3: the buoyancy scene of Fig. 9.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Paper4Buoyancy {
    pub bodies: usize,
    pub scene: String,
    pub resolution: u32,
    pub frames_per_second: f64,
    pub buoyancy_share: f64,
    pub peels_sphere_box: u32,
    pub peels_teapot_bunny_max: u32,
    pub peels_teapot_bunny_typical: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_tables_load() {
        let p = Published::get().expect("assets/paper_tables.toml loads");
        assert_eq!(p.paper1.table3.len(), 6);
        assert_eq!(p.paper1.table4.len(), 6);
        assert_eq!(p.paper4.object("bunny").map(|o| o.faces), Some(5110));
    }

    #[test]
    fn a_missing_cell_names_its_key() {
        let text = PAPER_TABLES_TOML.replacen("gpu_sigmoid = 0.031\n", "", 1);
        let e = Published::parse(&text).unwrap_err();
        assert!(e.contains("gpu_sigmoid"), "{e}");
    }

    #[test]
    fn a_mistyped_cell_names_its_key() {
        let text =
            PAPER_TABLES_TOML.replacen("frames_per_second = 16.0", "frames_per_second = \"16\"", 1);
        let e = Published::parse(&text).unwrap_err();
        assert!(e.contains("frames_per_second"), "{e}");
    }

    #[test]
    fn a_misspelt_key_is_refused() {
        let text = PAPER_TABLES_TOML.replacen("tri_test = 15.19", "tri_tset = 15.19", 1);
        let e = Published::parse(&text).unwrap_err();
        assert!(e.contains("tri_tset"), "{e}");
    }
}
