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

/// The width (CSS pixels) of a page's content: the body's 1100 less its padding of 1em (16
/// px) each side, as [`STYLE`] sets them. A figure wider than this is shown shrunk to it.
pub const CONTENT_WIDTH: u32 = 1100 - 2 * 16;

/// The width (CSS pixels) a table may take on a printed page (Letter or A4 less Chromium's
/// default margins, about 740), in the print style's table font: a table wider than this is
/// printed split into column groups ([`print_parts`]), never cut.
pub const PRINT_WIDTH: u32 = 700;

/// About how wide one character of a table prints, and a cell's padding and borders (CSS px).
const PRINT_CHAR: u32 = 7;
const PRINT_CELL_PADDING: u32 = 14;

/// The narrowest a column can print: its longest unbreakable piece (a cell's longest word; a
/// number cell whole, since numbers keep to one line), in CSS pixels.
pub fn print_min_width(cells: &[(&str, bool)]) -> u32 {
    cells
        .iter()
        .map(|&(cell, number)| {
            let longest = if number {
                cell.chars().count()
            } else {
                cell.split([' ', '/', '_', ',', '(', '-'])
                    .map(|w| w.chars().count())
                    .max()
                    .unwrap_or(0)
            };
            longest as u32 * PRINT_CHAR + PRINT_CELL_PADDING
        })
        .max()
        .unwrap_or(PRINT_CELL_PADDING)
}

/// The column groups a table of these column widths prints in: each group starts with column
/// 0 (the rows' names) and fits [`PRINT_WIDTH`] where it can (a column wider than that alone
/// gets a group of its own). One group, every column, when the table fits.
pub fn print_parts(widths: &[u32]) -> Vec<Vec<usize>> {
    let Some((&first, rest)) = widths.split_first() else {
        return Vec::new();
    };
    let mut parts: Vec<Vec<usize>> = Vec::new();
    let mut current = vec![0];
    let mut used = first;
    for (i, &w) in rest.iter().enumerate() {
        if used + w > PRINT_WIDTH && current.len() > 1 {
            parts.push(std::mem::replace(&mut current, vec![0]));
            used = first;
        }
        current.push(i + 1);
        used += w;
    }
    parts.push(current);
    parts
}

/// The page's style. Tables: text cells and every header wrap at spaces and at the separators
/// of long words ([`escape_cell`]); a word is broken (`overflow-wrap:break-word`) only where it
/// fits no line, so "llvmpipe" never becomes "llv mpi pe" in a narrow column. Only number
/// cells stay on one line. A table still wider than the page scrolls in its box, with a
/// scrollbar drawn at all times (not an overlay that shows only while scrolling). Printed, no
/// box scrolls: a table wider than the paper is printed as column groups (`.print`, made by the
/// page from [`print_parts`]) in place of the scrolling table (`.screen`), and no row, picture
/// or figure is split across pages.
pub const STYLE: &str =
    "body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;\
color:#222}div.table{margin:1em 0}div.scroll{overflow-x:auto;max-width:100%;\
scrollbar-width:auto;scrollbar-color:#888 #eee}div.scroll::-webkit-scrollbar{height:12px;\
background:#eee}div.scroll::-webkit-scrollbar-thumb{background:#888;border-radius:6px}\
table{border-collapse:collapse;font-size:90%}p.caption{text-align:left;font-weight:bold;\
margin:0;padding:.3em 0}td,th{border:1px solid #bbb;padding:.25em .5em;text-align:left;\
vertical-align:top;overflow-wrap:break-word}td.num,th.num{text-align:right}\
td.num{white-space:nowrap}th{background:#eee}td.yes{color:#060}td.no{color:#a00}\
td.unjudged{color:#666}img{max-width:100%;height:auto;border:1px solid #ddd}\
figure{margin:1em 0}.note{background:#ffd;padding:.5em 1em;border:1px solid #dd8}\
.print{display:none}@media print{body{max-width:none;margin:0;padding:0}\
div.scroll{overflow:visible}table{font-size:75%}tr,img,figure{break-inside:avoid}\
p.caption{break-after:avoid}div.table{break-inside:avoid-page}\
.print{display:block}.screen{display:none}}";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_content_width_is_the_styles() {
        assert!(STYLE.contains("max-width:1100px;margin:2em auto;padding:0 1em"));
        assert_eq!(CONTENT_WIDTH, 1068);
    }

    #[test]
    fn a_wide_table_prints_in_groups_that_fit_each_starting_with_the_names() {
        let widths = [90, 60, 60, 120, 200, 200, 200, 60, 60, 400, 900, 30];
        let parts = print_parts(&widths);
        let mut seen: Vec<usize> = parts.iter().flat_map(|p| p[1..].to_vec()).collect();
        seen.sort_unstable();
        assert_eq!(seen, (1..widths.len()).collect::<Vec<_>>(), "{parts:?}");
        for part in &parts {
            assert_eq!(part[0], 0);
            let width: u32 = part.iter().map(|&c| widths[c]).sum();
            assert!(width <= PRINT_WIDTH || part.len() == 2, "{part:?}: {width}");
        }
        assert_eq!(print_parts(&[100, 100, 100]), vec![vec![0, 1, 2]]);
        assert!(print_parts(&[]).is_empty());
        // A number stays whole; text breaks at spaces and separators.
        assert_eq!(
            print_min_width(&[("129884.25", true)]),
            9 * PRINT_CHAR + PRINT_CELL_PADDING
        );
        assert_eq!(
            print_min_width(&[("intimate animals (stand-in)", false)]),
            8 * PRINT_CHAR + PRINT_CELL_PADDING
        );
    }
}
