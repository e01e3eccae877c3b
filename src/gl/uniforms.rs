//! Which uniforms a program has. Setting one by name is checked against the declarations in
//! the program's own files, not against what the driver kept: a compiler may remove a
//! uniform the shader never reads (its location is then -1), and which ones it removes
//! differs between drivers. So a name the files declare but the driver dropped is set as a
//! no-op, and a name they do not declare is an error, on every driver alike.

use super::shaders::ShaderSource;
use std::collections::{BTreeSet, HashMap};

/// The uniforms of one program, by the name its files give them.
#[derive(Debug, Default)]
pub(super) struct Declared {
    /// Uniforms settable by name (an array or a struct by its own name).
    pub names: BTreeSet<String>,
    /// Members of uniform blocks, and the block each is in: set through a buffer, not by name.
    pub block_members: HashMap<String, String>,
}

impl Declared {
    /// What the files of a program declare.
    pub fn parse(sources: &[ShaderSource]) -> Declared {
        let mut declared = Declared::default();
        for source in sources {
            declared.add_source(source.source);
        }
        declared
    }

    fn add_source(&mut self, text: &str) {
        let text = strip_comments_and_directives(text);
        let tokens = tokens(&text);
        let mut i = 0;
        while i < tokens.len() {
            if tokens[i] == "uniform" {
                i = self.add_declaration(&tokens, i + 1);
            } else {
                i += 1;
            }
        }
    }

    /// Parse the declaration after a `uniform` keyword at `i`; returns where it ends.
    fn add_declaration(&mut self, t: &[&str], mut i: usize) -> usize {
        while i < t.len() && PRECISION.contains(&t[i]) {
            i += 1;
        }
        let Some(&type_or_block) = t.get(i) else {
            return i;
        };
        i += 1;
        if type_or_block == "struct" {
            // `uniform struct [Name] { ... } name;`
            if t.get(i).is_some_and(|s| is_identifier(s)) {
                i += 1;
            }
            i = skip_balanced(t, i, "{", "}");
        } else if t.get(i) == Some(&"{") {
            // A uniform block: `uniform Block { type member; ... } [instance];`
            let end = skip_balanced(t, i, "{", "}");
            for member in declarator_names(&t[i + 1..end.saturating_sub(1)]) {
                self.block_members
                    .insert(member.to_string(), type_or_block.to_string());
            }
            return end;
        }
        let end = t[i..]
            .iter()
            .position(|&s| s == ";")
            .map_or(t.len(), |p| i + p);
        self.names
            .extend(declarator_list(&t[i..end]).map(str::to_string));
        end
    }

    /// A uniform the driver reports active but the files do not show (declared through a
    /// macro): the driver knows better than this parser.
    pub fn add_active(&mut self, name: &str) {
        let base = base_name(name);
        if !self.block_members.contains_key(base) {
            self.names.insert(base.to_string());
        }
    }
}

/// `u_rows[3]` and `u_light.colour` are set through the uniforms `u_rows` and `u_light`.
pub(super) fn base_name(name: &str) -> &str {
    name.split(['[', '.']).next().unwrap_or(name).trim()
}

const PRECISION: [&str; 4] = ["lowp", "mediump", "highp", "precise"];

/// The names of a declarator list `a, b[3], c = 1.0` (after the type).
fn declarator_list<'a>(t: &[&'a str]) -> impl Iterator<Item = &'a str> {
    let mut names = Vec::new();
    let mut expect_name = true;
    let mut depth = 0i32;
    for &s in t {
        match s {
            "[" | "(" => depth += 1,
            "]" | ")" => depth -= 1,
            "," if depth == 0 => expect_name = true,
            _ if expect_name && depth == 0 && is_identifier(s) => {
                names.push(s);
                expect_name = false;
            }
            _ => {}
        }
    }
    names.into_iter()
}

/// The member names of the body of a uniform block: `type a, b; layout(...) type c[2]; ...`.
fn declarator_names<'a>(body: &[&'a str]) -> Vec<&'a str> {
    body.split(|&s| s == ";")
        .flat_map(|member| {
            // Skip the layout and precision qualifiers and the type; the names follow.
            let member: Vec<&str> = strip_layout(member);
            let first_name = member
                .iter()
                .take_while(|s| PRECISION.contains(s) || *s == &"row_major")
                .count()
                + 1;
            declarator_list(member.get(first_name..).unwrap_or(&[])).collect::<Vec<_>>()
        })
        .collect()
}

fn strip_layout<'a>(t: &[&'a str]) -> Vec<&'a str> {
    match t.iter().position(|&s| s == "layout") {
        Some(p) if t.get(p + 1) == Some(&"(") => {
            let end = skip_balanced(t, p + 1, "(", ")");
            t[..p].iter().chain(&t[end..]).copied().collect()
        }
        _ => t.to_vec(),
    }
}

/// The index just past the bracket that closes the one at `i` (or `i` if none is there).
fn skip_balanced(t: &[&str], i: usize, open: &str, close: &str) -> usize {
    if t.get(i) != Some(&open) {
        return i;
    }
    let mut depth = 0;
    for (k, &s) in t.iter().enumerate().skip(i) {
        if s == open {
            depth += 1;
        } else if s == close {
            depth -= 1;
            if depth == 0 {
                return k + 1;
            }
        }
    }
    t.len()
}

fn is_identifier(s: &str) -> bool {
    s.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
}

/// The source without comments and preprocessor lines (a `#define` is not a declaration).
fn strip_comments_and_directives(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix("//") {
            rest = after.find('\n').map_or("", |n| &after[n..]);
        } else if let Some(after) = rest.strip_prefix("/*") {
            rest = after.find("*/").map_or("", |n| &after[n + 2..]);
            out.push(' ');
        } else {
            let c = rest.chars().next().expect("not empty");
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    out.lines()
        .filter(|l| !l.trim_start().starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Identifiers, numbers and single punctuation characters.
fn tokens(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut chars = text.char_indices().peekable();
    while let Some((start, c)) = chars.next() {
        if c.is_whitespace() {
            continue;
        }
        let mut end = start + c.len_utf8();
        if c.is_ascii_alphanumeric() || c == '_' {
            while let Some(&(i, d)) = chars.peek() {
                let number_part = c.is_ascii_digit() && d == '.';
                if !(d.is_ascii_alphanumeric() || d == '_' || number_part) {
                    break;
                }
                end = i + d.len_utf8();
                chars.next();
            }
        }
        out.push(&text[start..end]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Declared {
        Declared::parse(&[ShaderSource {
            name: "t",
            source: text,
        }])
    }

    fn names(d: &Declared) -> Vec<&str> {
        d.names.iter().map(String::as_str).collect()
    }

    #[test]
    fn plain_array_and_list_declarations() {
        let d = parse(
            "#version 330 core\n\
             uniform mat4 u_mvp;\n\
             uniform highp vec4 u_rows[3 * BONES], u_b; // uniform float u_comment;\n\
             /* uniform float u_block_comment; */\n\
             layout(location = 0) out vec4 o;\n\
             uniform float u_init = 1.5, u_last;\n\
             #define uniform_macro 1\n\
             float not_uniform;\n",
        );
        assert_eq!(names(&d), ["u_b", "u_init", "u_last", "u_mvp", "u_rows"]);
    }

    #[test]
    fn blocks_and_structs() {
        let d = parse(
            "uniform Lights { layout(row_major) mat4 m; vec4 colour[2], dir; } lights;\n\
             uniform Bare { float x; };\n\
             uniform struct Light { vec3 p; } u_light;\n\
             struct S { float f; };\n\
             uniform S u_s[2];\n",
        );
        assert_eq!(names(&d), ["u_light", "u_s"]);
        let mut members: Vec<_> = d.block_members.iter().collect();
        members.sort();
        assert_eq!(
            members
                .iter()
                .map(|(m, b)| format!("{b}.{m}"))
                .collect::<Vec<_>>(),
            ["Lights.colour", "Lights.dir", "Lights.m", "Bare.x"]
        );
    }

    #[test]
    fn base_names_of_elements_and_members() {
        assert_eq!(base_name("u_rows[3]"), "u_rows");
        assert_eq!(base_name("u_light.colour"), "u_light");
        assert_eq!(base_name("u_mvp"), "u_mvp");
    }
}
