//! `selftest`: does this renderer do classic GPGPU right? A small fixed workload of every
//! paper and of every GL feature the papers are built from, each compared with its CPU
//! reference on data the check makes, with the tolerance stated beside it. One line per
//! check, a JSON object, or a JUnit XML file for CI systems.
//!
//! The checks are deliberately small (a few seconds in all on llvmpipe): they answer "same
//! answer as the CPU on this renderer", not "how fast".

mod gl_features;
mod papers;

use crate::gl::Context;
use crate::page::html::xml_escape;
use serde::Serialize;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

/// One check: its name, what it exercises, and the function that runs it. The function
/// returns what it compared (the detail line) or an error saying what differed.
pub struct Check {
    pub name: &'static str,
    /// `gl` for the building blocks, else the paper's section id (`paper1` .. `lecture3`).
    pub group: &'static str,
    pub run: fn(&Context) -> anyhow::Result<String>,
}

/// Every check, GL features first, then the papers in order.
pub fn checks() -> Vec<Check> {
    let mut all = gl_features::checks();
    all.extend(papers::checks());
    all
}

/// What one check found.
#[derive(Clone, Debug, Serialize)]
pub struct Outcome {
    pub name: String,
    pub group: String,
    pub passed: bool,
    /// What was compared and how close it came, or what differed.
    pub detail: String,
    pub seconds: f64,
}

/// A whole run, as `selftest --json` prints it.
#[derive(Clone, Debug, Serialize)]
pub struct SelfTest {
    pub renderer: String,
    pub passed: usize,
    pub failed: usize,
    pub seconds: f64,
    pub checks: Vec<Outcome>,
}

impl SelfTest {
    pub fn all_passed(&self) -> bool {
        self.failed == 0
    }
}

/// Runs `checks` on `ctx` in order. A check that errors or panics is a failure; the others
/// still run.
pub fn run(ctx: &Context, checks: &[Check]) -> SelfTest {
    let start = Instant::now();
    let outcomes: Vec<Outcome> = checks.iter().map(|c| run_one(ctx, c)).collect();
    let passed = outcomes.iter().filter(|o| o.passed).count();
    SelfTest {
        renderer: ctx.info().renderer_line(),
        passed,
        failed: outcomes.len() - passed,
        seconds: start.elapsed().as_secs_f64(),
        checks: outcomes,
    }
}

fn run_one(ctx: &Context, check: &Check) -> Outcome {
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| (check.run)(ctx)));
    let (passed, detail) = match result {
        Ok(Ok(detail)) => (true, detail),
        Ok(Err(e)) => (false, format!("{e:#}")),
        Err(panic) => {
            let message = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            (false, format!("panicked: {message}"))
        }
    };
    Outcome {
        name: check.name.into(),
        group: check.group.into(),
        passed,
        detail,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// One line per check: `PASS`/`FAIL`, group, name, detail.
pub fn to_text(run: &SelfTest) -> String {
    let mut out = format!("renderer: {}\n", run.renderer);
    for o in &run.checks {
        out.push_str(&format!(
            "{} {:<8} {:<28} {}\n",
            if o.passed { "PASS" } else { "FAIL" },
            o.group,
            o.name,
            o.detail
        ));
    }
    out.push_str(&format!(
        "{} passed, {} failed ({:.1} s)\n",
        run.passed, run.failed, run.seconds
    ));
    out
}

/// The run as a JUnit XML report: one test suite named after the renderer, one test case per
/// check (class name `classic_gpgpu.selftest.<group>`), a `<failure>` for each failed one.
pub fn to_junit(run: &SelfTest) -> String {
    let mut xml = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    xml.push_str(&format!(
        "<testsuites name=\"classic-gpgpu selftest\" tests=\"{}\" failures=\"{}\" time=\"{:.3}\">\n",
        run.checks.len(),
        run.failed,
        run.seconds
    ));
    xml.push_str(&format!(
        "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" skipped=\"0\" time=\"{:.3}\">\n",
        xml_escape(&run.renderer),
        run.checks.len(),
        run.failed,
        run.seconds
    ));
    for o in &run.checks {
        let open = format!(
            "    <testcase classname=\"classic_gpgpu.selftest.{}\" name=\"{}\" time=\"{:.3}\"",
            xml_escape(&o.group),
            xml_escape(&o.name),
            o.seconds
        );
        if o.passed {
            xml.push_str(&format!(
                "{open}>\n      <system-out>{}</system-out>\n    </testcase>\n",
                xml_escape(&o.detail)
            ));
        } else {
            xml.push_str(&format!(
                "{open}>\n      <failure message=\"{}\">{}</failure>\n    </testcase>\n",
                xml_escape(&o.detail),
                xml_escape(&o.detail)
            ));
        }
    }
    xml.push_str("  </testsuite>\n</testsuites>\n");
    xml
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outcome(name: &str, passed: bool, detail: &str) -> Outcome {
        Outcome {
            name: name.into(),
            group: "gl".into(),
            passed,
            detail: detail.into(),
            seconds: 0.25,
        }
    }

    #[test]
    fn junit_counts_failures_and_escapes_details() {
        let run = SelfTest {
            renderer: "llvmpipe <LLVM & co>".into(),
            passed: 1,
            failed: 1,
            seconds: 0.5,
            checks: vec![
                outcome("ok", true, "fine"),
                outcome("bad", false, "got \"1 < 2\"\nand more"),
            ],
        };
        let xml = to_junit(&run);
        assert!(xml.contains("tests=\"2\" failures=\"1\""), "{xml}");
        assert!(
            xml.contains("name=\"llvmpipe &lt;LLVM &amp; co&gt;\""),
            "{xml}"
        );
        assert_eq!(xml.matches("<testcase ").count(), 2);
        assert_eq!(xml.matches("<failure ").count(), 1);
        assert!(
            xml.contains("got &quot;1 &lt; 2&quot;&#10;and more"),
            "{xml}"
        );
        let text = to_text(&run);
        assert!(text.contains("PASS gl       ok"), "{text}");
        assert!(text.contains("FAIL gl       bad"), "{text}");
    }
}
