//! The learner's GL calls beside the solution's, as a two-column listing aligned call by call
//! (a longest common subsequence, so one extra or missing call shifts nothing after it), the
//! first difference marked `>>` and shown in full below, every other differing row `*`, and
//! long runs of equal rows folded. Both runs start on a fresh context, so the same calls make
//! the same object ids.

use crate::gl::trace::TracedCall;

/// One row: a call of each side, or of one side only where the other has nothing there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row<'a> {
    pub yours: Option<&'a TracedCall>,
    pub theirs: Option<&'a TracedCall>,
}

impl Row<'_> {
    /// Both sides made the same call.
    pub fn same(&self) -> bool {
        match (self.yours, self.theirs) {
            (Some(a), Some(b)) => same_call(a, b),
            _ => false,
        }
    }
}

/// The same function with the same arguments and result (the pass a call belongs to aside).
fn same_call(a: &TracedCall, b: &TracedCall) -> bool {
    a.function == b.function && a.args == b.args && a.result == b.result
}

/// Alignments beyond this many cells (calls x calls) pair the calls by their index instead.
const MOST_CELLS: usize = 4_000_000;

/// The two lists of calls aligned: equal calls on one row, and between them the calls of each
/// side paired in order, the longer side's rest on rows of its own.
pub fn align<'a>(yours: &'a [TracedCall], theirs: &'a [TracedCall]) -> Vec<Row<'a>> {
    let (n, m) = (yours.len(), theirs.len());
    if n.saturating_mul(m) > MOST_CELLS {
        return (0..n.max(m))
            .map(|i| Row {
                yours: yours.get(i),
                theirs: theirs.get(i),
            })
            .collect();
    }
    // longest[i][j]: the longest common subsequence of yours[i..] and theirs[j..].
    let mut longest = vec![vec![0u32; m + 1]; n + 1];
    for i in (0..n).rev() {
        for j in (0..m).rev() {
            longest[i][j] = if same_call(&yours[i], &theirs[j]) {
                longest[i + 1][j + 1] + 1
            } else {
                longest[i + 1][j].max(longest[i][j + 1])
            };
        }
    }
    let mut rows = Vec::new();
    let (mut i, mut j) = (0, 0);
    let (mut only_yours, mut only_theirs) = (Vec::new(), Vec::new());
    while i < n || j < m {
        if i < n && j < m && same_call(&yours[i], &theirs[j]) {
            pair_up(&mut rows, &mut only_yours, &mut only_theirs);
            rows.push(Row {
                yours: Some(&yours[i]),
                theirs: Some(&theirs[j]),
            });
            i += 1;
            j += 1;
        } else if j == m || (i < n && longest[i + 1][j] >= longest[i][j + 1]) {
            only_yours.push(&yours[i]);
            i += 1;
        } else {
            only_theirs.push(&theirs[j]);
            j += 1;
        }
    }
    pair_up(&mut rows, &mut only_yours, &mut only_theirs);
    rows
}

/// The calls of each side between two equal rows, side by side in order.
fn pair_up<'a>(
    rows: &mut Vec<Row<'a>>,
    yours: &mut Vec<&'a TracedCall>,
    theirs: &mut Vec<&'a TracedCall>,
) {
    for k in 0..yours.len().max(theirs.len()) {
        rows.push(Row {
            yours: yours.get(k).copied(),
            theirs: theirs.get(k).copied(),
        });
    }
    yours.clear();
    theirs.clear();
}

/// The index of the first row whose sides differ.
pub fn first_difference(rows: &[Row]) -> Option<usize> {
    rows.iter().position(|r| !r.same())
}

/// The width of each column.
const COLUMN: usize = 60;
/// Equal rows kept around a difference and at the ends when rows are folded.
const CONTEXT: usize = 2;

/// The listing: a heading, the rows (equal runs folded unless `full`), and the first
/// difference in full.
pub fn lines(
    yours: &[TracedCall],
    theirs: &[TracedCall],
    solution: &str,
    full: bool,
) -> Vec<String> {
    let rows = align(yours, theirs);
    let Some(first) = first_difference(&rows) else {
        return vec![format!(
            "your {} GL calls are the solution's ({solution}), call for call",
            yours.len()
        )];
    };
    let differing = match rows.iter().filter(|r| !r.same()).count() {
        1 => "1 row differs".to_string(),
        n => format!("{n} rows differ"),
    };
    let mut out = vec![
        format!(
            "your GL calls ({}) beside the solution's ({}, {solution}): {differing}, the first \
             is row {}, marked >>",
            yours.len(),
            theirs.len(),
            first + 1
        ),
        format!("{:>7}  {:<COLUMN$}   solution", "row", "yours"),
    ];
    let near_difference = |k: usize| {
        let lo = k.saturating_sub(CONTEXT);
        let hi = (k + CONTEXT + 1).min(rows.len());
        rows[lo..hi].iter().any(|r| !r.same())
    };
    let shown = |k: usize| full || k < CONTEXT || k + CONTEXT >= rows.len() || near_difference(k);
    let mut k = 0;
    while k < rows.len() {
        let hidden = (k..rows.len()).take_while(|&j| !shown(j)).count();
        // A fold of fewer than three rows would save nothing.
        if hidden >= 3 {
            out.push(format!("         ... {hidden} rows alike ..."));
            k += hidden;
            continue;
        }
        let row = &rows[k];
        let mark = if k == first {
            ">>"
        } else if row.same() {
            "  "
        } else {
            " *"
        };
        out.push(format!(
            "{mark}{:>5}  {:<COLUMN$} | {}",
            k + 1,
            cell(row.yours),
            cell(row.theirs)
        ));
        k += 1;
    }
    let row = &rows[first];
    out.push(format!("the first difference, row {}, in full:", first + 1));
    out.push(format!("  yours:    {}", whole(row.yours)));
    out.push(format!("  solution: {}", whole(row.theirs)));
    out
}

/// One line for a run stopped at a gap: how its calls so far compare with the solution's first.
pub fn so_far(yours: &[TracedCall], theirs: &[TracedCall], solution: &str) -> String {
    let differ = yours
        .iter()
        .zip(theirs)
        .position(|(a, b)| !same_call(a, b))
        .or((yours.len() > theirs.len()).then_some(theirs.len()));
    match differ {
        None => format!(
            "your {} GL calls so far are the first {} of the solution's ({solution}), call for \
             call",
            yours.len(),
            yours.len()
        ),
        Some(k) => format!(
            "your GL calls so far differ from the solution's ({solution}) at call {}: yours {}, \
             the solution's {} (the listing side by side comes once every gap is filled)",
            k + 1,
            whole(yours.get(k)),
            whole(theirs.get(k))
        ),
    }
}

fn whole(call: Option<&TracedCall>) -> String {
    call.map_or_else(|| "(no call)".to_string(), |c| c.to_string())
}

/// A call cut to the column's width.
fn cell(call: Option<&TracedCall>) -> String {
    let text = call.map_or_else(String::new, |c| c.to_string());
    if text.chars().count() <= COLUMN {
        text
    } else {
        let cut: String = text.chars().take(COLUMN - 3).collect();
        format!("{cut}...")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn call(function: &'static str, args: &str) -> TracedCall {
        TracedCall {
            pass: None,
            function,
            args: args.into(),
            result: None,
        }
    }

    #[test]
    fn one_extra_call_shifts_nothing_after_it() {
        let theirs = [call("glA", ""), call("glB", ""), call("glC", "")];
        let yours = [
            call("glA", ""),
            call("glExtra", ""),
            call("glB", ""),
            call("glC", ""),
        ];
        let rows = align(&yours, &theirs);
        assert_eq!(rows.len(), 4);
        assert_eq!(first_difference(&rows), Some(1));
        assert!(rows[1].theirs.is_none());
        assert!(rows[2].same() && rows[3].same());
    }

    #[test]
    fn a_changed_argument_is_one_row_marked_and_shown_in_full() {
        let theirs = [call("glTexImage2D", "GL_R32F"), call("glDraw", "")];
        let yours = [call("glTexImage2D", "GL_RGBA8"), call("glDraw", "")];
        let rows = align(&yours, &theirs);
        assert_eq!(rows.len(), 2);
        let text = lines(&yours, &theirs, "s.rs", false).join("\n");
        assert!(text.contains(">>    1"), "{text}");
        assert!(text.contains("yours:    glTexImage2D(GL_RGBA8)"), "{text}");
        assert!(text.contains("solution: glTexImage2D(GL_R32F)"), "{text}");
    }

    #[test]
    fn equal_lists_say_so_and_long_equal_runs_fold() {
        let same: Vec<TracedCall> = (0..30).map(|_| call("glX", "")).collect();
        assert!(lines(&same, &same, "s.rs", false)[0].contains("call for call"));
        let mut yours = same.clone();
        yours[20] = call("glY", "");
        let text = lines(&yours, &same, "s.rs", false).join("\n");
        assert!(text.contains("rows alike"), "{text}");
        assert!(!lines(&yours, &same, "s.rs", true)
            .join("\n")
            .contains("rows alike"));
        assert!(so_far(&same[..5], &same, "s.rs").contains("first 5"));
        assert!(so_far(&yours[..25], &same, "s.rs").contains("at call 21"));
    }
}
