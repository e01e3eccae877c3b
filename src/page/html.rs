//! The HTML every page shares: escaping a text for a page or a table cell (and for the XML of
//! a JUnit report), and the style sheet. The report, the course's guide and the `compare` page
//! are all written with it, so they read alike and a text from a `results.json` is escaped the
//! same way everywhere.

/// `text` with the characters HTML gives a meaning (`&`, `<`, `>`, `"`) escaped.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Escapes text for an XML attribute or element; drops the control characters XML 1.0 does
/// not allow.
pub fn xml_escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\n' => out.push_str("&#10;"),
            '\t' | '\r' => out.push(' '),
            c if (c as u32) < 0x20 => {}
            c => out.push(c),
        }
    }
    out
}

/// A word longer than this may break after a separator (a path, a list without spaces).
const LONG_WORD: usize = 16;

/// `text` escaped for a table cell, with a break opportunity (`<wbr>`) after each `/`, `_`,
/// `.`, `,`, `:`, `=` and `(` inside a long word: cells wrap at spaces and there, never in the
/// middle of a word such as "llvmpipe" (the style's `overflow-wrap:break-word` breaks only a
/// word that fits no line at all).
pub fn escape_cell(text: &str) -> String {
    let words: Vec<String> = text
        .split(' ')
        .map(|word| {
            if word.chars().count() <= LONG_WORD {
                return escape(word);
            }
            let mut out = String::new();
            for c in word.chars() {
                out.push_str(&escape(c.encode_utf8(&mut [0; 4])));
                if matches!(c, '/' | '_' | '.' | ',' | ':' | '=' | '(') {
                    out.push_str("<wbr>");
                }
            }
            out
        })
        .collect();
    words.join(" ")
}

/// The page's style. Tables: text cells and every header wrap at spaces and at the separators
/// of long words ([`escape_cell`]); a word is broken (`overflow-wrap:break-word`) only where it
/// fits no line, so "llvmpipe" never becomes "llv mpi pe" in a narrow column. Only number
/// cells stay on one line. A table still wider than the page scrolls in its box, with a
/// scrollbar drawn at all times (not an overlay that shows only while scrolling).
pub const STYLE: &str =
    "body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;\
color:#222}div.table{margin:1em 0}div.scroll{overflow-x:auto;max-width:100%;\
scrollbar-width:auto;scrollbar-color:#888 #eee}div.scroll::-webkit-scrollbar{height:12px;\
background:#eee}div.scroll::-webkit-scrollbar-thumb{background:#888;border-radius:6px}\
table{border-collapse:collapse;font-size:90%}p.caption{text-align:left;font-weight:bold;\
margin:0;padding:.3em 0}td,th{border:1px solid #bbb;padding:.25em .5em;text-align:left;\
vertical-align:top;overflow-wrap:break-word}td.num,th.num{text-align:right}\
td.num{white-space:nowrap}th{background:#eee}td.yes{color:#060}td.no{color:#a00}\
td.unjudged{color:#666}img{max-width:100%;border:1px solid #ddd}figure{margin:1em 0}\
.note{background:#ffd;padding:.5em 1em;border:1px solid #dd8}";
