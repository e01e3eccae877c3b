//! A per-pass profiler: where the time of a run goes, pass by pass, so that the fixed costs of
//! a renderer (synchronous waits, per-pass set-up) show beside the work itself.
//!
//! Off by default and free when off (one flag test per pass). When [`start`]ed on a context,
//! every [`Pass`](super::Pass) draw is recorded under its pass name, and code may open its own
//! named [`scope`]s around several passes. For each name the table gives:
//! - GPU time, from a pair of `GL_TIMESTAMP` queries around each scope (timestamps nest, so
//!   they never clash with the [`TimerQuery`](super::TimerQuery)s the benchmarks use). The
//!   results are read later, when the renderer says they are available, never in the same
//!   frame: reading them must not add the waits the profiler is there to show.
//!   On a tile-based software renderer (llvmpipe) a timestamp is taken as each rasterizer
//!   thread reaches the query in its last tile, so passes that share one scene (no wait
//!   between them) get spans that overlap or collapse: read the GPU column there together
//!   with the waits, which is where the rasterization of the passes before them happens.
//!   A draw that samples a texture rendered since the last wait also waits, inside the draw
//!   call: its wall time then holds the rasterization of the pass that wrote the texture.
//! - wall time of the scope (on a software renderer, issuing a draw is cheap and the work
//!   happens in the next wait);
//! - time spent waiting inside it: `glFinish`, `glReadPixels` and buffer reads, query results.
//!   Each kind of wait also has its own row, so the waits of a run add up in one place.

use super::Context;
use serde::Serialize;
use std::collections::VecDeque;
use std::fmt;
use std::time::{Duration, Instant};

/// Pending timestamp pairs beyond which the oldest are polled (polling makes a software
/// renderer flush, so it is done rarely).
const POLL_AFTER: usize = 64;

/// The profiler's state, held by the context while profiling is on.
pub(super) struct State {
    rows: Vec<Row>,
    /// The rows of the scopes now open, innermost last.
    open: Vec<usize>,
    pending: VecDeque<Pending>,
    spare: Vec<glow::Query>,
    started: Instant,
    timestamps: bool,
}

struct Row {
    name: String,
    depth: usize,
    calls: u64,
    gpu_ns: u64,
    gpu_samples: u64,
    wall: Duration,
    wait: Duration,
}

struct Pending {
    row: usize,
    begin: glow::Query,
    end: glow::Query,
}

/// Start profiling on `ctx` (a profile already running starts again, empty).
pub fn start(ctx: &Context) {
    start_with(ctx, true);
}

/// Start profiling wall time and waits only, without GPU timestamps: for runs whose own
/// timings must not carry the profiler's queries (a software renderer bins each timestamp
/// into every tile of the target).
pub fn start_wall_only(ctx: &Context) {
    start_with(ctx, false);
}

fn start_with(ctx: &Context, gpu: bool) {
    let timestamps = gpu && ctx.timestamp_bits() > 0;
    let old = ctx.inner.profile.replace(Some(Box::new(State {
        rows: Vec::new(),
        open: Vec::new(),
        pending: VecDeque::new(),
        spare: Vec::new(),
        started: Instant::now(),
        timestamps,
    })));
    if let Some(old) = old {
        old.delete(ctx);
    }
}

/// Whether a profile is running on `ctx`.
pub fn is_on(ctx: &Context) -> bool {
    ctx.inner
        .profile
        .try_borrow()
        .map(|p| p.is_some())
        .unwrap_or(false)
}

/// Stop profiling and return the table (`None` when no profile was running). Reads every
/// timestamp still pending, which waits for the GPU.
pub fn finish(ctx: &Context) -> Option<ProfileTable> {
    let mut state = ctx.inner.profile.borrow_mut().take()?;
    let wall = state.started.elapsed();
    while let Some(p) = state.pending.pop_front() {
        state.resolve(ctx, p);
    }
    let table = ProfileTable {
        renderer: ctx.info().renderer_line(),
        wall_ms: ms(wall),
        rows: state
            .rows
            .iter()
            .map(|r| ProfileRow {
                name: r.name.clone(),
                depth: r.depth,
                calls: r.calls,
                gpu_ms: (r.gpu_samples > 0).then_some(r.gpu_ns as f64 * 1e-6),
                wall_ms: ms(r.wall),
                wait_ms: ms(r.wait),
            })
            .collect(),
    };
    state.delete(ctx);
    Some(table)
}

/// A named scope: recorded from [`scope`] until dropped.
#[must_use = "the scope ends when this is dropped"]
pub struct Scope<'a> {
    ctx: &'a Context,
    open: Option<(usize, Instant, Option<glow::Query>)>,
}

/// Open a scope named `name` (a no-op unless a profile is running).
pub fn scope<'a>(ctx: &'a Context, name: &str) -> Scope<'a> {
    open_scope(ctx, name, true)
}

/// Open a scope for CPU work (a CPU baseline, a decode): wall time and waits only. The GPU
/// clock keeps running while the CPU works, so a GPU time of CPU work would mean nothing.
pub fn cpu_scope<'a>(ctx: &'a Context, name: &str) -> Scope<'a> {
    open_scope(ctx, name, false)
}

fn open_scope<'a>(ctx: &'a Context, name: &str, gpu: bool) -> Scope<'a> {
    let mut guard = ctx.inner.profile.borrow_mut();
    let open = guard.as_mut().map(|state| {
        state.poll(ctx);
        let row = state.row(name);
        let begin = if gpu { state.timestamp(ctx) } else { None };
        state.open.push(row);
        (row, Instant::now(), begin)
    });
    Scope { ctx, open }
}

impl Drop for Scope<'_> {
    fn drop(&mut self) {
        let Some((row, start, begin)) = self.open.take() else {
            return;
        };
        let mut guard = self.ctx.inner.profile.borrow_mut();
        let Some(state) = guard.as_mut() else {
            return;
        };
        let end = match begin {
            Some(_) => state.timestamp(self.ctx),
            None => None,
        };
        let r = &mut state.rows[row];
        r.calls += 1;
        r.wall += start.elapsed();
        if let Some(pos) = state.open.iter().rposition(|&o| o == row) {
            state.open.remove(pos);
        }
        match (begin, end) {
            (Some(begin), Some(end)) => state.pending.push_back(Pending { row, begin, end }),
            (b, e) => state.spare.extend(b.into_iter().chain(e)),
        }
    }
}

/// Run `work`, a wait for the GPU of kind `kind` (`glFinish`, `glReadPixels`, ...), and add
/// its wall time to every open scope and to the row of its kind.
pub fn wait<T>(ctx: &Context, kind: &str, work: impl FnOnce() -> T) -> T {
    if !is_on(ctx) {
        return work();
    }
    let start = Instant::now();
    let value = work();
    let took = start.elapsed();
    if let Some(state) = ctx.inner.profile.borrow_mut().as_mut() {
        for &row in &state.open {
            state.rows[row].wait += took;
        }
        let depth = state.open.len();
        let row = state.row_at(&format!("wait: {kind}"), depth);
        let r = &mut state.rows[row];
        r.calls += 1;
        r.wall += took;
        r.wait += took;
    }
    value
}

impl State {
    /// The row of `name` as a child of the innermost open scope.
    fn row(&mut self, name: &str) -> usize {
        self.row_at(name, self.open.len())
    }

    fn row_at(&mut self, name: &str, depth: usize) -> usize {
        if let Some(i) = self.rows.iter().position(|r| r.name == name) {
            return i;
        }
        // A new row goes after its parent's last descendant, so nesting reads top-down.
        let at = match self.open.last() {
            Some(&parent) => {
                let mut i = parent + 1;
                while i < self.rows.len() && self.rows[i].depth > self.rows[parent].depth {
                    i += 1;
                }
                i
            }
            None => self.rows.len(),
        };
        self.rows.insert(
            at,
            Row {
                name: name.to_string(),
                depth,
                calls: 0,
                gpu_ns: 0,
                gpu_samples: 0,
                wall: Duration::ZERO,
                wait: Duration::ZERO,
            },
        );
        // Indices at or after `at` moved down by one.
        for o in &mut self.open {
            if *o >= at {
                *o += 1;
            }
        }
        for p in &mut self.pending {
            if p.row >= at {
                p.row += 1;
            }
        }
        at
    }

    /// A `GL_TIMESTAMP` query issued now (`None` where the renderer has no timestamps).
    fn timestamp(&mut self, ctx: &Context) -> Option<glow::Query> {
        if !self.timestamps {
            return None;
        }
        let gl = ctx.gl();
        let query = match self.spare.pop() {
            Some(q) => q,
            None => unsafe { gl.create_query() }.ok()?,
        };
        unsafe { gl.query_counter(query, glow::TIMESTAMP) };
        Some(query)
    }

    /// Read the oldest pairs whose results are in, once many are pending.
    fn poll(&mut self, ctx: &Context) {
        if self.pending.len() < POLL_AFTER {
            return;
        }
        while let Some(p) = self.pending.front() {
            let ready = unsafe {
                ctx.gl()
                    .get_query_parameter_u32(p.end, glow::QUERY_RESULT_AVAILABLE)
                    != 0
            };
            if !ready {
                break;
            }
            let p = self.pending.pop_front().expect("a front");
            self.resolve(ctx, p);
        }
    }

    fn resolve(&mut self, ctx: &Context, p: Pending) {
        let read = |q: glow::Query| {
            let mut value: u64 = 0;
            // SAFETY: no query buffer is ever bound, so glow's "offset" is the address written.
            unsafe {
                ctx.gl().get_query_parameter_u64_with_offset(
                    q,
                    glow::QUERY_RESULT,
                    &mut value as *mut u64 as usize,
                )
            };
            value
        };
        let (begin, end) = (read(p.begin), read(p.end));
        let r = &mut self.rows[p.row];
        r.gpu_ns += end.saturating_sub(begin);
        r.gpu_samples += 1;
        self.spare.push(p.begin);
        self.spare.push(p.end);
    }

    fn delete(self, ctx: &Context) {
        let gl = ctx.gl();
        for q in self
            .spare
            .into_iter()
            .chain(self.pending.into_iter().flat_map(|p| [p.begin, p.end]))
        {
            unsafe { gl.delete_query(q) };
        }
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// One row of the table: a pass, a scope or a kind of wait.
#[derive(Clone, Debug, Serialize)]
pub struct ProfileRow {
    pub name: String,
    /// Nesting depth (0: outermost).
    pub depth: usize,
    pub calls: u64,
    /// Summed GPU time by timestamp queries; `None` where the renderer has no timestamps.
    pub gpu_ms: Option<f64>,
    /// Summed wall time.
    pub wall_ms: f64,
    /// Summed time waiting for the GPU inside it.
    pub wait_ms: f64,
}

/// What [`finish`] returns: every pass and scope, in the order first seen, nested.
#[derive(Clone, Debug, Serialize)]
pub struct ProfileTable {
    pub renderer: String,
    /// Wall time from [`start`] to [`finish`].
    pub wall_ms: f64,
    pub rows: Vec<ProfileRow>,
}

impl ProfileTable {
    /// Total wall time waiting for the GPU (the `wait:` rows).
    pub fn wait_ms(&self) -> f64 {
        self.rows
            .iter()
            .filter(|r| r.name.starts_with("wait: "))
            .map(|r| r.wall_ms)
            .sum()
    }

    /// The row named `name`.
    pub fn row(&self, name: &str) -> Option<&ProfileRow> {
        self.rows.iter().find(|r| r.name == name)
    }
}

impl fmt::Display for ProfileTable {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        writeln!(f, "per-pass profile ({})", self.renderer)?;
        let width = self
            .rows
            .iter()
            .map(|r| r.name.chars().count() + 2 * r.depth)
            .max()
            .unwrap_or(4)
            .max(4);
        writeln!(
            f,
            "{:<width$}  {:>7}  {:>10}  {:>10}  {:>10}  {:>10}",
            "pass", "calls", "GPU ms", "wall ms", "wait ms", "wall/call"
        )?;
        for r in &self.rows {
            let name = format!("{}{}", "  ".repeat(r.depth), r.name);
            let gpu = r
                .gpu_ms
                .map(|g| format!("{g:.2}"))
                .unwrap_or_else(|| "-".into());
            writeln!(
                f,
                "{name:<width$}  {:>7}  {gpu:>10}  {:>10.2}  {:>10.2}  {:>10.3}",
                r.calls,
                r.wall_ms,
                r.wait_ms,
                r.wall_ms / r.calls.max(1) as f64
            )?;
        }
        write!(
            f,
            "total wall {:.1} ms, of which waiting for the GPU {:.1} ms",
            self.wall_ms,
            self.wait_ms()
        )
    }
}
