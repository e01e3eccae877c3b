//! A per-pass profile: where the time of a frame goes. Each GPU pass is bracketed by two
//! timestamp queries (`glQueryCounter`, which, unlike `TIME_ELAPSED`, may sit inside another
//! timer query) and by the wall clock of issuing it; waits (reading a query or a texture
//! back) and CPU steps count wall time only. The queries are read when the table is asked
//! for, after the work, so profiling adds no wait of its own to the frame.

use super::{Context, GlError};
use glow::HasContext;
use serde::Serialize;
use std::cell::RefCell;
use std::rc::Rc;
use std::time::Instant;

/// What a row measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// Draws and clears: GPU time by timestamps, wall time of issuing them.
    Pass,
    /// The CPU waiting for the GPU (a query result, a read-back).
    Wait,
    /// CPU work between passes.
    Cpu,
}

/// One line of the table: every span of one name.
#[derive(Clone, Debug, Serialize)]
pub struct ProfileRow {
    pub name: String,
    pub kind: Kind,
    pub count: usize,
    /// Sum of the GPU time between each span's timestamps (passes only), milliseconds.
    pub gpu_ms: f64,
    /// Sum of the wall time of each span, milliseconds.
    pub wall_ms: f64,
}

struct Span {
    row: usize,
    queries: Option<(glow::Query, glow::Query)>,
}

#[derive(Default)]
struct Inner {
    rows: Vec<ProfileRow>,
    spans: Vec<Span>,
    free: Vec<glow::Query>,
}

/// Collects spans; cheap to clone (the clones share the table).
#[derive(Clone)]
pub struct Profiler {
    owned: Rc<Owned>,
}

impl Profiler {
    pub fn new(ctx: &Context) -> Profiler {
        Profiler {
            owned: Rc::new(Owned {
                ctx: ctx.clone(),
                inner: RefCell::default(),
            }),
        }
    }

    /// A GPU pass (or several of one name): timestamps around `work`, and its wall time.
    pub fn pass<T>(
        &self,
        name: &str,
        work: impl FnOnce() -> Result<T, GlError>,
    ) -> Result<T, GlError> {
        let (start, end) = (self.query()?, self.query()?);
        let gl = self.owned.ctx.gl();
        unsafe { gl.query_counter(start, glow::TIMESTAMP) };
        let t = Instant::now();
        let result = work();
        let wall = t.elapsed().as_secs_f64() * 1e3;
        unsafe { gl.query_counter(end, glow::TIMESTAMP) };
        self.record(name, Kind::Pass, wall, Some((start, end)));
        result
    }

    /// The CPU waiting on the GPU: wall time only.
    pub fn wait<T>(&self, name: &str, work: impl FnOnce() -> T) -> T {
        self.timed(name, Kind::Wait, work)
    }

    /// CPU work: wall time only.
    pub fn cpu<T>(&self, name: &str, work: impl FnOnce() -> T) -> T {
        self.timed(name, Kind::Cpu, work)
    }

    fn timed<T>(&self, name: &str, kind: Kind, work: impl FnOnce() -> T) -> T {
        let t = Instant::now();
        let result = work();
        self.record(name, kind, t.elapsed().as_secs_f64() * 1e3, None);
        result
    }

    fn query(&self) -> Result<glow::Query, GlError> {
        if let Some(q) = self.owned.inner.borrow_mut().free.pop() {
            return Ok(q);
        }
        unsafe { self.owned.ctx.gl().create_query() }.map_err(GlError::Invalid)
    }

    fn record(
        &self,
        name: &str,
        kind: Kind,
        wall_ms: f64,
        queries: Option<(glow::Query, glow::Query)>,
    ) {
        let mut inner = self.owned.inner.borrow_mut();
        let row = match inner
            .rows
            .iter()
            .position(|r| r.name == name && r.kind == kind)
        {
            Some(i) => i,
            None => {
                inner.rows.push(ProfileRow {
                    name: name.to_string(),
                    kind,
                    count: 0,
                    gpu_ms: 0.0,
                    wall_ms: 0.0,
                });
                inner.rows.len() - 1
            }
        };
        inner.rows[row].count += 1;
        inner.rows[row].wall_ms += wall_ms;
        if queries.is_some() {
            inner.spans.push(Span { row, queries });
        }
    }

    /// The table so far, rows in the order they first appeared (reads the pending
    /// timestamps: call it after the work).
    pub fn rows(&self) -> Result<Vec<ProfileRow>, GlError> {
        let gl = self.owned.ctx.gl();
        let mut inner = self.owned.inner.borrow_mut();
        let spans = std::mem::take(&mut inner.spans);
        for span in spans {
            if let Some((start, end)) = span.queries {
                let read = |q: glow::Query| -> u64 {
                    let mut value: u64 = 0;
                    // SAFETY: no query buffer is bound, so the "offset" is the address written.
                    unsafe {
                        gl.get_query_parameter_u64_with_offset(
                            q,
                            glow::QUERY_RESULT,
                            &mut value as *mut u64 as usize,
                        )
                    };
                    value
                };
                let ns = read(end).saturating_sub(read(start));
                inner.rows[span.row].gpu_ms += ns as f64 * 1e-6;
                inner.free.extend([start, end]);
            }
        }
        self.owned
            .ctx
            .check("reading the profile's timestamp queries")?;
        Ok(inner.rows.clone())
    }

    /// Forget the rows (keep the query objects for reuse).
    pub fn reset(&self) -> Result<(), GlError> {
        self.rows()?;
        self.owned.inner.borrow_mut().rows.clear();
        Ok(())
    }
}

struct Owned {
    ctx: Context,
    inner: RefCell<Inner>,
}

impl Drop for Owned {
    fn drop(&mut self) {
        let inner = self.inner.get_mut();
        let pending = inner.spans.iter().filter_map(|s| s.queries);
        let all: Vec<glow::Query> = pending
            .flat_map(|(a, b)| [a, b])
            .chain(inner.free.iter().copied())
            .collect();
        for q in all {
            unsafe { self.ctx.gl().delete_query(q) };
        }
    }
}

/// The rows as a text table (totals last).
pub fn table(rows: &[ProfileRow]) -> String {
    let mut s = format!(
        "{:<40} {:>5} {:>7} {:>11} {:>11} {:>11}\n",
        "pass", "kind", "count", "GPU ms", "wall ms", "wall/call"
    );
    let kind = |k: Kind| match k {
        Kind::Pass => "pass",
        Kind::Wait => "wait",
        Kind::Cpu => "cpu",
    };
    for r in rows {
        let gpu = if r.kind == Kind::Pass {
            format!("{:.3}", r.gpu_ms)
        } else {
            "-".into()
        };
        s += &format!(
            "{:<40} {:>5} {:>7} {:>11} {:>11.3} {:>11.4}\n",
            r.name,
            kind(r.kind),
            r.count,
            gpu,
            r.wall_ms,
            r.wall_ms / r.count.max(1) as f64
        );
    }
    let sum = |k: Kind| -> f64 { rows.iter().filter(|r| r.kind == k).map(|r| r.wall_ms).sum() };
    let gpu: f64 = rows.iter().map(|r| r.gpu_ms).sum();
    s += &format!(
        "{:<40} {:>5} {:>7} {:>11.3} {:>11.3}   (passes {:.3}, waits {:.3}, cpu {:.3})\n",
        "total",
        "",
        "",
        gpu,
        sum(Kind::Pass) + sum(Kind::Wait) + sum(Kind::Cpu),
        sum(Kind::Pass),
        sum(Kind::Wait),
        sum(Kind::Cpu)
    );
    s
}
