//! Named regions of the project's own files, cut out at guide time so a page shows the code
//! as it is (issue 39): a region starts at a line `// region: NAME` and ends at the next
//! `// endregion` at the same depth, in Rust and in GLSL alike. Regions may nest; the marker
//! lines of inner regions are left out of what is cut.
//!
//! Every Rust file under `src/` and every shader is compiled into the binary (`build.rs`), so
//! the guide needs no checkout. A name the guide asks for that is missing or empty is an error
//! naming the file and the region, and a test asks for every region the guide names.

use crate::gl::shaders;

include!(concat!(env!("OUT_DIR"), "/rust_sources.rs"));

/// The line that opens a region; the name follows it.
pub const START: &str = "// region:";
/// The line that closes the innermost open region.
pub const END: &str = "// endregion";

/// A region cut out of a file: its lines without the markers, their common indent removed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Region {
    /// The file, a repository path such as `src/learn/reduction.rs` or `glsl/learn/saxpy.frag`.
    pub file: &'static str,
    pub name: String,
    /// The 1-based line in `file` of the region's first line of code.
    pub first_line: usize,
    pub text: String,
}

/// The text of a project file (a Rust file under `src/` or a shader), as compiled in.
pub fn file_text(file: &str) -> Option<(&'static str, &'static str)> {
    RUST.iter()
        .find(|(name, _)| *name == file)
        .copied()
        .or_else(|| shaders::find(file).map(|s| (s.name, s.source)))
}

/// The region `name` of `file`. Errors name the file and the region: a file that is not the
/// project's, a region that is missing, unclosed, repeated or has no code.
pub fn cut(file: &str, name: &str) -> Result<Region, String> {
    let (file, text) = file_text(file)
        .ok_or_else(|| format!("{file}: not a Rust file under src/ or a shader of the project"))?;
    let matches: Vec<Region> = all_in(file, text)?
        .into_iter()
        .filter(|r| r.name == name)
        .collect();
    match matches.as_slice() {
        [] => Err(format!(
            "{file}: no region `{name}` (a line `{START} {name}` ... `{END}`)"
        )),
        [region] if region.text.trim().is_empty() => {
            Err(format!("{file}: region `{name}` is empty"))
        }
        [region] => Ok(region.clone()),
        _ => Err(format!(
            "{file}: region `{name}` is named {} times",
            matches.len()
        )),
    }
}

/// The region `name` of `text`, the text of `file`: a file that is not compiled in with the
/// others (an example's solution, which the library includes itself).
pub fn cut_text(file: &'static str, text: &str, name: &str) -> Result<Region, String> {
    let matches: Vec<Region> = all_in(file, text)?
        .into_iter()
        .filter(|r| r.name == name)
        .collect();
    match matches.as_slice() {
        [region] if !region.text.trim().is_empty() => Ok(region.clone()),
        [_] => Err(format!("{file}: region `{name}` is empty")),
        [] => Err(format!(
            "{file}: no region `{name}` (a line `{START} {name}` ... `{END}`)"
        )),
        _ => Err(format!(
            "{file}: region `{name}` is named {} times",
            matches.len()
        )),
    }
}

/// The names of the regions of `file`, in the order they open.
pub fn names(file: &str) -> Result<Vec<String>, String> {
    let (file, text) =
        file_text(file).ok_or_else(|| format!("{file}: not a file of the project"))?;
    Ok(all_in(file, text)?.into_iter().map(|r| r.name).collect())
}

/// Every region of `text`, in the order they open, with an error for a marker out of place.
fn all_in(file: &'static str, text: &str) -> Result<Vec<Region>, String> {
    // The regions still open: (name, first line, lines so far); each line of code goes to all.
    let mut open: Vec<(String, usize, Vec<&str>)> = Vec::new();
    let mut done = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if let Some(name) = trimmed.strip_prefix(START) {
            let name = name.trim();
            if name.is_empty() {
                return Err(format!("{file}:{}: a region with no name", index + 1));
            }
            open.push((name.to_string(), index + 2, Vec::new()));
        } else if trimmed == END {
            let (name, first_line, lines) = open
                .pop()
                .ok_or_else(|| format!("{file}:{}: `{END}` with no region open", index + 1))?;
            done.push((
                first_line,
                Region {
                    file,
                    name,
                    first_line,
                    text: dedent(&lines),
                },
            ));
        } else {
            for region in &mut open {
                region.2.push(line);
            }
        }
    }
    if let Some((name, first_line, _)) = open.pop() {
        return Err(format!(
            "{file}:{}: region `{name}` is never closed by `{END}`",
            first_line - 1
        ));
    }
    done.sort_by_key(|(first, _)| *first);
    Ok(done.into_iter().map(|(_, r)| r).collect())
}

/// `lines` joined, with the indent they all share removed and blank lines at the ends dropped.
fn dedent(lines: &[&str]) -> String {
    let indent = lines
        .iter()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.len() - l.trim_start().len())
        .min()
        .unwrap_or(0);
    let body: Vec<&str> = lines
        .iter()
        .map(|l| {
            if l.trim().is_empty() {
                ""
            } else {
                &l[indent..]
            }
        })
        .collect();
    let first = body
        .iter()
        .position(|l| !l.is_empty())
        .unwrap_or(body.len());
    let last = body
        .iter()
        .rposition(|l| !l.is_empty())
        .map_or(first, |i| i + 1);
    body[first..last].join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "fn f() {\n    // region: outer\n    let a = 1;\n    // region: inner\n    let b = a + 1;\n    // endregion\n    // endregion\n    // region: empty\n\n    // endregion\n}\n";

    #[test]
    fn regions_nest_and_lose_their_markers_and_indent() {
        let regions = all_in("x.rs", TEXT).unwrap();
        let names: Vec<&str> = regions.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["outer", "inner", "empty"]);
        assert_eq!(regions[0].text, "let a = 1;\nlet b = a + 1;");
        assert_eq!(regions[0].first_line, 3);
        assert_eq!(regions[1].text, "let b = a + 1;");
        assert_eq!(regions[1].first_line, 5);
        assert_eq!(regions[2].text, "");
    }

    #[test]
    fn markers_out_of_place_are_errors_naming_the_line() {
        let unclosed = all_in("x.rs", "// region: a\nlet x = 1;\n").unwrap_err();
        assert!(
            unclosed.contains("x.rs:1") && unclosed.contains("`a`"),
            "{unclosed}"
        );
        let stray = all_in("x.rs", "let x = 1;\n// endregion\n").unwrap_err();
        assert!(stray.contains("x.rs:2"), "{stray}");
    }

    #[test]
    fn missing_and_unknown_are_errors_naming_file_and_region() {
        let missing = cut("src/learn/regions.rs", "no-such-region").unwrap_err();
        assert!(missing.contains("src/learn/regions.rs") && missing.contains("no-such-region"));
        assert!(cut("src/nothing.rs", "a")
            .unwrap_err()
            .contains("src/nothing.rs"));
    }

    #[test]
    fn rust_files_and_shaders_are_both_found() {
        assert!(file_text("src/learn/regions.rs").is_some());
        assert!(file_text("glsl/learn/saxpy.frag").is_some());
    }
}
