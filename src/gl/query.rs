//! Occlusion queries (how many samples passed: paper 4's "until no fragment", CULLIDE's
//! visibility test), timer queries (the GPU time of a pass) and fragment shader invocation
//! queries (how often a shader ran: pipeline statistics).

use super::{Context, GlError};

struct Query {
    ctx: Context,
    id: glow::Query,
    target: u32,
}

impl Drop for Query {
    fn drop(&mut self) {
        unsafe { self.ctx.gl().delete_query(self.id) };
    }
}

impl Query {
    fn new(ctx: &Context, target: u32) -> Result<Query, GlError> {
        let id = unsafe { ctx.gl().create_query() }.map_err(GlError::Invalid)?;
        Ok(Query {
            ctx: ctx.clone(),
            id,
            target,
        })
    }
    fn begin(&self) {
        unsafe { self.ctx.gl().begin_query(self.target, self.id) };
    }
    fn end(&self) {
        unsafe { self.ctx.gl().end_query(self.target) };
    }
    /// Wait for the result.
    fn result(&self, what: &str) -> Result<u64, GlError> {
        let mut value: u64 = 0;
        // SAFETY: no query buffer is ever bound, so glow's "offset" is the address written to.
        super::profile::wait(&self.ctx, "query result", || unsafe {
            self.ctx.gl().get_query_parameter_u64_with_offset(
                self.id,
                glow::QUERY_RESULT,
                &mut value as *mut u64 as usize,
            )
        });
        self.ctx.check(what)?;
        Ok(value)
    }
    fn available(&self) -> bool {
        unsafe {
            self.ctx
                .gl()
                .get_query_parameter_u32(self.id, glow::QUERY_RESULT_AVAILABLE)
                != 0
        }
    }
}

/// Counts the samples that pass the depth and stencil tests between `begin` and `end`.
pub struct OcclusionQuery(Query);

impl OcclusionQuery {
    pub fn new(ctx: &Context) -> Result<OcclusionQuery, GlError> {
        Query::new(ctx, glow::SAMPLES_PASSED).map(OcclusionQuery)
    }
    pub fn begin(&self) {
        self.0.begin()
    }
    pub fn end(&self) {
        self.0.end()
    }
    /// The number of samples that passed (waits for the GPU).
    pub fn samples(&self) -> Result<u64, GlError> {
        let samples = self.0.result("reading an occlusion query")?;
        if let Some(gpu) = self.0.ctx.period() {
            gpu.check_occlusion_count(samples)?;
        }
        Ok(samples)
    }
    /// The samples of every query of `queries`, in order: one wait for the GPU (the first
    /// result) and one error check for all of them, as a pass of many queries reads them.
    pub fn samples_of(queries: &[OcclusionQuery]) -> Result<Vec<u64>, GlError> {
        let Some(first) = queries.first() else {
            return Ok(Vec::new());
        };
        let ctx = &first.0.ctx;
        let values: Vec<u64> = super::profile::wait(ctx, "query result", || {
            queries
                .iter()
                .map(|q| {
                    let mut value: u64 = 0;
                    // SAFETY: no query buffer is ever bound, so glow's "offset" is the
                    // address written to.
                    unsafe {
                        ctx.gl().get_query_parameter_u64_with_offset(
                            q.0.id,
                            glow::QUERY_RESULT,
                            &mut value as *mut u64 as usize,
                        )
                    };
                    value
                })
                .collect()
        });
        ctx.check("reading occlusion queries")?;
        if let Some(gpu) = ctx.period() {
            values
                .iter()
                .try_for_each(|&samples| gpu.check_occlusion_count(samples))?;
        }
        Ok(values)
    }
    /// Whether [`OcclusionQuery::samples`] would return without waiting.
    pub fn available(&self) -> bool {
        self.0.available()
    }
}

/// Counts the fragment shader's invocations between `begin` and `end`: the pipeline
/// statistics query of `GL_ARB_pipeline_statistics_query`, core in OpenGL 4.6. Unlike an
/// occlusion query, which counts the samples that pass the depth test, it counts the shader's
/// runs, whether the depth test came before them or after.
pub struct FragmentInvocationsQuery(Query);

/// The extension that brought pipeline statistics queries (before OpenGL 4.6).
pub const PIPELINE_STATISTICS_EXTENSION: &str = "GL_ARB_pipeline_statistics_query";

impl FragmentInvocationsQuery {
    /// Whether `ctx` has pipeline statistics queries.
    pub fn supported(ctx: &Context) -> bool {
        ctx.info().gl_version >= (4, 6)
            || ctx
                .gl()
                .supported_extensions()
                .contains(PIPELINE_STATISTICS_EXTENSION)
    }

    /// A query; an error naming what is missing where the context has no pipeline statistics.
    pub fn new(ctx: &Context) -> Result<FragmentInvocationsQuery, GlError> {
        if !Self::supported(ctx) {
            let info = ctx.info();
            return Err(GlError::Context(format!(
                "counting fragment shader invocations needs OpenGL 4.6 or                  {PIPELINE_STATISTICS_EXTENSION}, which this context (OpenGL {}.{}, {}) lacks",
                info.gl_version.0, info.gl_version.1, info.renderer
            )));
        }
        Query::new(ctx, glow::FRAGMENT_SHADER_INVOCATIONS).map(FragmentInvocationsQuery)
    }
    pub fn begin(&self) {
        self.0.begin()
    }
    pub fn end(&self) {
        self.0.end()
    }
    /// The number of fragment shader invocations counted (waits for the GPU).
    pub fn invocations(&self) -> Result<u64, GlError> {
        self.0.result("reading a fragment shader invocations query")
    }
}

/// Measures the GPU time of the commands between `begin` and `end`. Timer queries do not nest.
pub struct TimerQuery(Query);

impl TimerQuery {
    pub fn new(ctx: &Context) -> Result<TimerQuery, GlError> {
        Query::new(ctx, glow::TIME_ELAPSED).map(TimerQuery)
    }
    pub fn begin(&self) {
        self.0.begin()
    }
    pub fn end(&self) {
        self.0.end()
    }
    /// Elapsed GPU time in nanoseconds (waits for the GPU).
    pub fn nanoseconds(&self) -> Result<u64, GlError> {
        self.0.result("reading a timer query")
    }
    /// Elapsed GPU time in milliseconds (waits for the GPU).
    pub fn milliseconds(&self) -> Result<f64, GlError> {
        Ok(self.nanoseconds()? as f64 * 1e-6)
    }
}

/// Run `work` inside a timer query: its result and its GPU time in milliseconds.
pub fn time_gpu<T>(
    ctx: &Context,
    work: impl FnOnce() -> Result<T, GlError>,
) -> Result<(T, f64), GlError> {
    let query = TimerQuery::new(ctx)?;
    query.begin();
    let result = work();
    query.end();
    let value = result?;
    Ok((value, query.milliseconds()?))
}
