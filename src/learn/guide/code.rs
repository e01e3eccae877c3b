//! The code on each lesson page, cut out of the files at guide time (issue 39): the shaders a
//! lesson runs, whole, and the host code of each pass, by named region. [`LESSONS`] is the one
//! list of what every page shows; a test walks it and cuts every region it names, so a region
//! renamed or emptied in a lesson's file fails the build's tests, not the reader.
//!
//! Each block is printed with its file and first line, and holds exactly that file's lines
//! (their shared indent removed): a page cannot drift from the code that ran.

use crate::learn::regions;
use crate::learn::LessonInfo;
use crate::page::html::escape;

/// One region a page shows: the file, the region's name, and a sentence that goes above it.
#[derive(Clone, Copy, Debug)]
pub struct Shown {
    pub file: &'static str,
    pub region: &'static str,
    pub caption: &'static str,
}

/// The host code of one lesson's passes, in the order the lesson runs them.
#[derive(Clone, Copy, Debug)]
pub struct LessonCode {
    /// The lesson's id (`learn <id>`).
    pub lesson: &'static str,
    pub host: &'static [Shown],
}

const fn shown(file: &'static str, region: &'static str, caption: &'static str) -> Shown {
    Shown {
        file,
        region,
        caption,
    }
}

const TEXTURE_IS_ARRAY: &str = "src/learn/texture_is_array.rs";
const QUAD_IS_LOOP: &str = "src/learn/quad_is_loop.rs";
const PING_PONG: &str = "src/learn/ping_pong.rs";
const REDUCTION: &str = "src/learn/reduction.rs";
const HISTOGRAM_PYRAMID: &str = "src/learn/histogram_pyramid.rs";
const SEVERAL_OUTPUTS: &str = "src/learn/several_outputs.rs";
const SCATTER: &str = "src/learn/scatter_and_blend.rs";
const COUNT_AND_MASK: &str = "src/learn/count_and_mask.rs";
const DEPTH_PEELING: &str = "src/learn/depth_peeling.rs";
const READBACK: &str = "src/learn/readback_and_upload.rs";
const RENDER_TO_VBO: &str = "src/learn/render_to_vertex_buffer.rs";
const COMPUTE_REDUCTION: &str = "src/learn/compute_reduction.rs";
const DEBUGGING: &str = "src/learn/debugging.rs";

/// Every lesson page's host code: the one table the guide and its test read.
pub const LESSONS: &[LessonCode] = &[
    LessonCode {
        lesson: "texture-is-array",
        host: &[
            shown(TEXTURE_IS_ARRAY, "upload", "The array goes up: a texture made from the CPU's floats, one value per texel."),
            shown(TEXTURE_IS_ARRAY, "copy-into-format", "The same array drawn into a target of each format and read back: the format decides what survives."),
            shown(TEXTURE_IS_ARRAY, "sample-texel-centres", "Sampling with linear filtering, once at texel centres and once at their corners."),
            shown(TEXTURE_IS_ARRAY, "compute-read", "The compute counterpart: one invocation per texel reads it by index into a storage buffer."),
        ],
    },
    LessonCode {
        lesson: "quad-is-loop",
        host: &[
            shown(QUAD_IS_LOOP, "saxpy-upload", "The two input arrays become two textures."),
            shown(QUAD_IS_LOOP, "saxpy-pass", "The loop: a target texture, its framebuffer, the program, the inputs bound to samplers, a uniform, and one rectangle drawn over the whole target; then the result is read back."),
            shown(QUAD_IS_LOOP, "gather-pass", "A gather: the body reads an index from one texture and the value it names from another."),
            shown(QUAD_IS_LOOP, "saxpy-compute", "The compute counterpart: the same body over storage buffers, dispatched once per element."),
        ],
    },
    LessonCode {
        lesson: "ping-pong",
        host: &[
            shown(PING_PONG, "ping-pong-setup", "Two textures, each with its own framebuffer."),
            shown(PING_PONG, "ping-pong-step", "Each step reads one texture and draws into the other; the roles swap after every step."),
            shown(PING_PONG, "jacobi-compute", "The compute counterpart swaps two storage buffers the same way, with a barrier between steps."),
        ],
    },
    LessonCode {
        lesson: "reduction",
        host: &[
            shown(REDUCTION, "reduce-level", "One level per pass: a target fan times smaller on each side, each texel combining the block below it, until one texel is left."),
            shown(REDUCTION, "reduce-compute", "The compute counterpart: the project's shared-memory reducer, once for the sum and once for the maximum."),
        ],
    },
    LessonCode {
        lesson: "several-outputs",
        host: &[
            shown(SEVERAL_OUTPUTS, "mrt-pass", "One framebuffer with two colour attachments: one draw writes both."),
            shown(SEVERAL_OUTPUTS, "integrands-compute", "The compute counterpart writes the same values into two storage buffers."),
        ],
    },
    LessonCode {
        lesson: "scatter-and-blend",
        host: &[
            shown(SCATTER, "scatter-program", "A vertex shader that moves each point to its bin, and a fragment shader that writes 1."),
            shown(SCATTER, "scatter-pass", "One point per value, drawn without vertex buffers; additive blending turns the writes into counts."),
            shown(SCATTER, "histogram-compute", "The compute counterpart counts with atomic additions."),
        ],
    },
    LessonCode {
        lesson: "count-and-mask",
        host: &[
            shown(COUNT_AND_MASK, "count-pass", "Counting: an occlusion query around a pass whose shader discards what is not counted."),
            shown(COUNT_AND_MASK, "depth-pass", "The depth mask: the condition written as depth, no colour."),
            shown(COUNT_AND_MASK, "stencil-pass", "The stencil mask: 1 where the slot holds real data."),
            shown(COUNT_AND_MASK, "work-pass", "The work pass, tested against both masks and counted by a query."),
            shown(COUNT_AND_MASK, "count-and-mask-compute", "The compute counterpart: the test is an if, the count an atomic counter."),
        ],
    },
    LessonCode {
        lesson: "depth-peeling",
        host: &[
            shown(DEPTH_PEELING, "peel-targets", "Two depth textures and two framebuffers sharing one picture: each layer writes one depth and reads the other."),
            shown(DEPTH_PEELING, "peel-pass", "Each layer is a draw of the mesh that keeps only what lies behind the previous layer; a query says when nothing is left."),
            shown(DEPTH_PEELING, "ray-cast", "The compute counterpart casts one ray per pixel through every triangle."),
        ],
    },
    LessonCode {
        lesson: "readback-and-upload",
        host: &[
            shown(READBACK, "upload-pbo", "An upload from a pixel unpack buffer: the call only queues the copy."),
            shown(READBACK, "full-readback", "The whole array read back with glReadPixels: the CPU waits for it."),
            shown(READBACK, "block-flags", "A small pass flags the blocks that hold anything, into level 0 of a histogram pyramid; the pyramid is built on it."),
            shown(HISTOGRAM_PYRAMID, "pyramid-levels", "Each level of the pyramid sums 2x2 texels of the one below, up to the count at the top."),
            shown(HISTOGRAM_PYRAMID, "pyramid-list", "Each slot of the list walks down the pyramid to its flagged block."),
            shown(HISTOGRAM_PYRAMID, "pyramid-gather", "The flagged blocks are gathered into one small texture, in the list's order."),
            shown(READBACK, "read-compacted", "Then two reads bring back the list and the blocks, however many are flagged."),
            shown(READBACK, "compact", "The compute counterpart compacts the non-zero texels with an atomic counter."),
        ],
    },
    LessonCode {
        lesson: "render-to-vertex-buffer",
        host: &[
            shown(RENDER_TO_VBO, "pass-1", "Pass 1 writes one vertex per texel."),
            shown(RENDER_TO_VBO, "pbo-to-vbo", "The target read into a pixel pack buffer, then copied into the vertex buffer: the data never leaves the GPU."),
            shown(RENDER_TO_VBO, "pass-2", "Pass 2 draws that buffer as points."),
            shown(RENDER_TO_VBO, "transform-feedback", "The later way: the vertex shader's outputs captured by transform feedback."),
            shown(RENDER_TO_VBO, "positions-compute", "The compute counterpart writes the vertices into a storage buffer."),
        ],
    },
    LessonCode {
        lesson: "compute-reduction",
        host: &[
            shown(COMPUTE_REDUCTION, "reduce-passes", "Dispatches until one value is left: each work group reduces its share in shared memory and writes one result."),
        ],
    },
    LessonCode {
        lesson: "debugging",
        host: &[
            shown(DEBUGGING, "sample-off-centre", "Fault 1: the same row sampled at texel centres and off them."),
            shown(DEBUGGING, "feedback-loop-found", "Fault 3: a pass that samples its own target, found before anything is drawn."),
            shown(DEBUGGING, "ping-pong-fix", "Its fix: read one texture, draw into another."),
            shown(DEBUGGING, "incomplete-refused", "Fault 5: a depth texture attached as colour is refused when the framebuffer is made."),
            shown(DEBUGGING, "complete-framebuffer", "Its fix: the depth texture attached as depth."),
        ],
    },
];

/// The host regions of lesson `id` (none for a lesson the table does not list).
pub fn host_of(id: &str) -> &'static [Shown] {
    LESSONS
        .iter()
        .find(|l| l.lesson == id)
        .map_or(&[], |l| l.host)
}

/// One code block of a page: the file, its first line, the text (the file's lines).
#[derive(Clone, Debug)]
pub struct Block {
    pub file: &'static str,
    pub first_line: usize,
    pub text: String,
    pub caption: String,
}

/// A shader shown whole.
pub fn whole(file: &str) -> Result<Block, String> {
    let (file, text) = regions::file_text(file)
        .ok_or_else(|| format!("{file}: not a shader or Rust file of the project"))?;
    if text.trim().is_empty() {
        return Err(format!("{file}: empty"));
    }
    Ok(Block {
        file,
        first_line: 1,
        text: text.trim_end().to_string(),
        caption: String::new(),
    })
}

/// A region of a file, with its caption.
pub fn region(s: &Shown) -> Result<Block, String> {
    let r = regions::cut(s.file, s.region)?;
    Ok(Block {
        file: r.file,
        first_line: r.first_line,
        text: r.text,
        caption: s.caption.to_string(),
    })
}

/// Every block lesson `info`'s page shows: its shaders whole, then its host regions. An error
/// names the file and region that is missing or empty.
pub fn blocks(info: &LessonInfo) -> Result<(Vec<Block>, Vec<Block>), String> {
    let shaders = info
        .shaders
        .iter()
        .map(|s| whole(s))
        .collect::<Result<Vec<_>, _>>()?;
    let host = host_of(info.id)
        .iter()
        .map(region)
        .collect::<Result<Vec<_>, _>>()?;
    Ok((shaders, host))
}

/// A block as HTML: its caption, then `<pre>` naming the file and line, the code escaped.
/// Lines in `marked` (0-based within the block) are highlighted.
pub fn block_html(block: &Block, marked: &[usize]) -> String {
    let mut out = String::new();
    if !block.caption.is_empty() {
        out.push_str(&format!("<p>{}</p>\n", escape(&block.caption)));
    }
    let last = block.first_line + block.text.lines().count().max(1) - 1;
    out.push_str(&format!(
        "<div class=\"where\"><code>{}</code>, lines {}-{}</div>\n<pre class=\"code\" \
         data-file=\"{}\" data-line=\"{}\"><code>",
        escape(block.file),
        block.first_line,
        last,
        escape(block.file),
        block.first_line
    ));
    let lines: Vec<String> = block
        .text
        .lines()
        .enumerate()
        .map(|(k, line)| {
            if marked.contains(&k) {
                format!("<mark>{}</mark>", escape(line))
            } else {
                escape(line)
            }
        })
        .collect();
    out.push_str(&lines.join("\n"));
    out.push_str("</code></pre>\n");
    out
}

/// The lines of `a` and of `b` that are not in their longest common subsequence: where an
/// exercise template and its solution differ (the gap and its answer).
pub fn differing_lines(a: &str, b: &str) -> (Vec<usize>, Vec<usize>) {
    let (a, b): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    // common[i][j]: the longest common subsequence of a[i..] and b[j..].
    let mut common = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for i in (0..a.len()).rev() {
        for j in (0..b.len()).rev() {
            common[i][j] = if a[i] == b[j] {
                common[i + 1][j + 1] + 1
            } else {
                common[i + 1][j].max(common[i][j + 1])
            };
        }
    }
    let (mut i, mut j, mut only_a, mut only_b) = (0, 0, Vec::new(), Vec::new());
    while i < a.len() && j < b.len() {
        if a[i] == b[j] {
            i += 1;
            j += 1;
        } else if common[i + 1][j] >= common[i][j + 1] {
            only_a.push(i);
            i += 1;
        } else {
            only_b.push(j);
            j += 1;
        }
    }
    only_a.extend(i..a.len());
    only_b.extend(j..b.len());
    (only_a, only_b)
}

/// The code section of lesson `info`'s page: each shader whole, then the host code of each
/// pass with its caption. An error names the region that could not be cut.
pub fn code_section(info: &LessonInfo) -> Result<String, String> {
    let (shaders, host) = blocks(info)?;
    let mut out = String::from(
        "<h2>The code</h2>\n<p>Cut from the files when this guide was made: each block is the \
         file's own lines.</p>\n<h3>The shaders</h3>\n",
    );
    for block in &shaders {
        out.push_str(&block_html(block, &[]));
    }
    if !host.is_empty() {
        out.push_str("<h3>The host code of each pass</h3>\n");
        for block in &host {
            out.push_str(&block_html(block, &[]));
        }
    }
    Ok(out)
}

/// An exercise's template with its gap highlighted, and the solution behind a `<details>`
/// with the lines that fill the gap highlighted.
pub fn exercise_code(solution: &str) -> Result<String, String> {
    let template_file = format!(
        "{}{}",
        crate::gl::shaders::EXERCISES,
        solution.trim_start_matches("glsl/learn/")
    );
    let template = whole(&template_file)?;
    let answer = whole(solution)?;
    let (gap, filled) = differing_lines(&template.text, &answer.text);
    let mut out = String::from("<p>The template, its gap highlighted:</p>\n");
    out.push_str(&block_html(&template, &gap));
    out.push_str("<details><summary>The solution (the shipped shader)</summary>\n");
    out.push_str(&block_html(&answer, &filled));
    out.push_str("</details>\n");
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn differing_lines_find_the_gap() {
        let (a, b) = differing_lines("x\ny = 0;\nz", "x\ny = a * b;\nz\nw");
        assert_eq!(a, [1]);
        assert_eq!(b, [1, 3]);
    }

    #[test]
    fn every_lesson_in_the_table_exists() {
        let ids: Vec<&str> = crate::learn::all().iter().map(|l| l.info().id).collect();
        for l in LESSONS {
            assert!(ids.contains(&l.lesson), "no lesson {}", l.lesson);
        }
    }
}
