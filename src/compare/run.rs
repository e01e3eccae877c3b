//! One machine's run, read back from the `results.json` that `reproduce` wrote. A results.json
//! may come from anyone (a study collects them from many machines), so what one may hold is
//! bounded ([`MAX_BYTES`], [`MAX_DEPTH`], [`MAX_STRING`]) and a file past a bound is refused,
//! named, before it is parsed.

use crate::report::{provenance, Section};
use crate::timing::Load;
use anyhow::{bail, Context as _};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The renderer as `results.json` records it (the fields `compare` shows).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(default)]
struct RecordedRenderer {
    platform: String,
    vendor: String,
    renderer: String,
    version: String,
    glsl_version: String,
}

/// The largest results.json read: a full run at the papers' sizes is under 1 MiB.
pub const MAX_BYTES: u64 = 32 << 20;
/// The deepest nesting of arrays and objects: a run's is under 12.
pub const MAX_DEPTH: usize = 64;
/// The longest text (a JSON string, in bytes as written): a claim's measured text is a few
/// hundred.
pub const MAX_STRING: usize = 64 << 10;

/// `results.json`, as far as `compare` reads it. Fields a report from an older version lacks
/// are empty (and said to be missing where they matter).
#[derive(Deserialize)]
struct Recorded {
    renderer: RecordedRenderer,
    #[serde(default)]
    cpu: String,
    #[serde(default)]
    date: String,
    #[serde(default)]
    commit: String,
    /// The run-wide claims version of a run from before per-claim versions.
    #[serde(default)]
    claims_version: String,
    #[serde(default)]
    command_line: Vec<String>,
    quick: bool,
    #[serde(default)]
    runs: String,
    #[serde(default)]
    elapsed_s: f64,
    sections: Vec<Section>,
    /// How a run from before per-claim versions had them given afterwards (`claims --stamp`).
    #[serde(default)]
    stamped: String,
}

/// One machine: where its results came from, and its sections.
#[derive(Clone, Debug, Serialize)]
pub struct Run {
    /// The `results.json` it was read from, as given.
    pub file: String,
    /// The column's name: the renderer in a word or two ("llvmpipe", "zink", "NVIDIA H100
    /// 80GB HBM3"), numbered when two runs share it.
    pub label: String,
    pub renderer: String,
    pub platform: String,
    pub vendor: String,
    pub gl_version: String,
    pub glsl_version: String,
    pub cpu: String,
    pub date: String,
    pub commit: String,
    /// The version of the whole set of claims a run from before per-claim versions recorded
    /// (empty for a later run, whose claims carry their own).
    pub claims_version: String,
    pub command_line: Vec<String>,
    pub quick: bool,
    pub runs: String,
    pub elapsed_s: f64,
    /// The lowest and highest 1-minute load average at the start or end of any section.
    pub load: Option<(f64, f64)>,
    /// The cores the run could use.
    pub cores: usize,
    /// How the claims of a run from before per-claim versions had them given afterwards
    /// ([`super::stamp`]); empty for a run that recorded them itself.
    pub stamped: String,
    #[serde(skip)]
    pub sections: Vec<Section>,
}

impl Run {
    /// Reads `path`; the error names the file and what is wrong with it (a bound it passes
    /// included).
    pub fn read(path: &Path) -> anyhow::Result<Run> {
        let size = std::fs::metadata(path)
            .with_context(|| format!("reading {}", path.display()))?
            .len();
        if size > MAX_BYTES {
            bail!(
                "{}: refused: {size} bytes, more than the {MAX_BYTES} a results.json may hold",
                path.display()
            );
        }
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        check_bounds(&text).map_err(|e| anyhow::anyhow!("{}: refused: {e}", path.display()))?;
        let recorded: Recorded = serde_json::from_str(&text).map_err(|e| {
            anyhow::anyhow!(
                "{}: not a results.json of `classic-gpgpu reproduce` ({e}); give the \
                 results.json of a report folder",
                path.display()
            )
        })?;
        Ok(Run::from_recorded(path, recorded))
    }

    fn from_recorded(path: &Path, r: Recorded) -> Run {
        let loads: Vec<Load> = r
            .sections
            .iter()
            .flat_map(|s| [s.load_start, s.load_end])
            .flatten()
            .collect();
        let load = loads.iter().map(|l| l.one_minute).fold(None, |acc, v| {
            Some(acc.map_or((v, v), |(lo, hi): (f64, f64)| (lo.min(v), hi.max(v))))
        });
        Run {
            file: path.display().to_string(),
            label: short_name(&r.renderer.renderer),
            renderer: r.renderer.renderer,
            platform: r.renderer.platform,
            vendor: r.renderer.vendor,
            gl_version: r.renderer.version,
            glsl_version: r.renderer.glsl_version,
            cpu: r.cpu,
            date: r.date,
            commit: r.commit,
            claims_version: r.claims_version,
            command_line: r.command_line,
            quick: r.quick,
            runs: r.runs,
            elapsed_s: r.elapsed_s,
            load,
            cores: loads.first().map_or(0, |l| l.cores),
            stamped: r.stamped,
            sections: r.sections,
        }
    }

    /// Whether the run's claims carry their own ids and versions (a run made since they do).
    pub fn has_claim_versions(&self) -> bool {
        self.sections
            .iter()
            .flat_map(|s| &s.claims)
            .any(|c| !c.version.is_empty())
    }

    /// The section `id`, if the run has it.
    pub fn section(&self, id: &str) -> Option<&Section> {
        self.sections.iter().find(|s| s.id == id)
    }

    /// The commit in short ("b924125", "b924125-dirty"), or "not recorded".
    pub fn short_commit(&self) -> String {
        if self.commit.is_empty() {
            "not recorded".into()
        } else {
            provenance::short_commit(&self.commit)
        }
    }

    /// The day of the run ("2026-11-28"), or "no date".
    pub fn day(&self) -> &str {
        self.date.split_whitespace().next().unwrap_or("no date")
    }

    /// "load 0.52-1.90 on 2 cores", or "load not recorded".
    pub fn load_in_words(&self) -> String {
        match self.load {
            Some((lo, hi)) => format!("load {} on {} cores", range(lo, hi), self.cores),
            None => "load not recorded".into(),
        }
    }

    /// The command line as typed, program name shortened to its file name.
    pub fn command(&self) -> String {
        let mut words: Vec<String> = self.command_line.clone();
        if let Some(first) = words.first_mut() {
            if let Some(name) = Path::new(first.as_str()).file_name() {
                *first = name.to_string_lossy().into_owned();
            }
        }
        if words.is_empty() {
            "not recorded".into()
        } else {
            words.join(" ")
        }
    }

    /// The file name the run is kept under in `assets/results/`: `<machine>-<commit>.json`,
    /// the machine's name ending in `-quick` for a `--quick` run.
    pub fn kept_name(&self) -> String {
        format!(
            "{}{}-{}.json",
            slug(&short_name(&self.renderer)),
            if self.quick { "-quick" } else { "" },
            self.short_commit()
        )
    }
}

/// Refuses a text nested deeper than [`MAX_DEPTH`] or with a string longer than
/// [`MAX_STRING`], in one pass over the bytes before any parsing (a parser's own limits would
/// otherwise answer with a stack depth, or not at all).
pub fn check_bounds(text: &str) -> Result<(), String> {
    let (mut depth, mut in_string, mut escaped, mut string_len) = (0usize, false, false, 0usize);
    for (at, byte) in text.bytes().enumerate() {
        if in_string {
            string_len += 1;
            if string_len > MAX_STRING {
                return Err(format!(
                    "a text at byte {} is longer than the {MAX_STRING} bytes a results.json text \
                     may hold",
                    at + 1 - string_len
                ));
            }
            match (escaped, byte) {
                (true, _) => escaped = false,
                (false, b'\\') => escaped = true,
                (false, b'"') => in_string = false,
                _ => {}
            }
            continue;
        }
        match byte {
            b'"' => (in_string, string_len) = (true, 0),
            b'[' | b'{' => {
                depth += 1;
                if depth > MAX_DEPTH {
                    return Err(format!(
                        "nested more than {MAX_DEPTH} deep (at byte {at}); a results.json is \
                         not"
                    ));
                }
            }
            b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(())
}

/// "1.20" or "1.20-1.85".
pub fn range(lo: f64, hi: f64) -> String {
    if format!("{lo:.2}") == format!("{hi:.2}") {
        format!("{lo:.2}")
    } else {
        format!("{lo:.2}-{hi:.2}")
    }
}

/// A section's load in words: "load 0.52-1.90" (start to end, 1-minute average).
pub fn section_load(section: &Section) -> String {
    match (section.load_start, section.load_end) {
        (Some(a), Some(b)) => format!("load {:.2} to {:.2}", a.one_minute, b.one_minute),
        (Some(a), None) | (None, Some(a)) => format!("load {:.2}", a.one_minute),
        (None, None) => "load not recorded".into(),
    }
}

/// The renderer in a word or two: Mesa's drivers by name, a GPU up to its first `/` or `(`.
pub fn short_name(renderer: &str) -> String {
    let lower = renderer.to_lowercase();
    for driver in ["zink", "llvmpipe", "softpipe", "swrast", "swiftshader"] {
        if lower.starts_with(driver) {
            return driver.into();
        }
    }
    let cut = renderer.find(['/', '(']).unwrap_or(renderer.len());
    let name = renderer[..cut].trim();
    if name.is_empty() {
        "unknown renderer".into()
    } else {
        name.into()
    }
}

/// Lower case, runs of anything but letters and digits as one `-`.
pub fn slug(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    out.trim_matches('-').to_string()
}

/// Numbers labels that several runs share ("llvmpipe", "llvmpipe 2"), in order.
pub fn number_shared_labels(runs: &mut [Run]) {
    for i in 0..runs.len() {
        let same = runs[..i]
            .iter()
            .filter(|r| short_name(&r.renderer) == runs[i].label)
            .count();
        let later = runs[i + 1..]
            .iter()
            .any(|r| short_name(&r.renderer) == runs[i].label);
        if same > 0 {
            runs[i].label = format!("{} {}", runs[i].label, same + 1);
        } else if later {
            runs[i].label = format!("{} 1", runs[i].label);
        }
    }
}
