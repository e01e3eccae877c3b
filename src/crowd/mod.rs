//! Paper 2: Kang & Han, "Real-Time Animation of Large Crowds", ICEC 2006 (LNCS 4161).
//!
//! Skinning of large crowds in a pixel shader [section 2, Fig. 1-2]: vertex data and
//! per-frame bone matrices live in float textures; a draw call over a render target of
//! n characters x m vertices skins every vertex of those characters (pass 1); the target
//! is copied into a vertex buffer through a pixel buffer object (render-to-VBO); pass 2
//! draws every character from that buffer with a shared index buffer. Section 3 adds
//! three LOD meshes (1,084, 544, 312 polygons) and view-frustum culling, and compares with
//! skinning in the vertex shader (Table 1).
//!
//! Where this code differs from the paper:
//! - The paper skins all characters in a single draw call. Here one pass-1 draw holds at
//!   most [`pass1_skinning::characters_per_target`] characters: rows of at most 128
//!   characters (the vertex-stride cap of OpenGL 4.4+) stacked in blocks of m rows up to
//!   the largest texture, which is 3,712 characters of the 562-vertex soldier or 558-vertex
//!   horse at LOD 0 on 16384-texel targets. A larger crowd is split into batches, each with
//!   its own pass 1, copy and pass 2 ([`renderer`]).
//! - The characters are this project's procedural stand-ins ([`soldier`], [`horse`]): their
//!   bone counts (18 and 20), the soldier's spear and the walk and gallop clips are our
//!   choices, as are the distances at which the LOD changes ([`lod::LodPolicy`]) and the
//!   scenes' cameras ([`scene`]). The paper gives only the polygon counts, kept exactly.
//! - Sprites for the far field ([`sprites`]) and behaviour control ([`steering`]) are not in
//!   the paper (the tutorial's lecture 2 mentions both); sprites are off unless asked for.
//!
//! The paper's notation is kept: n characters, m vertices per character, a 3x4 bone
//! matrix stored as three rows. One file per step:
//!
//! - characters: [`skeleton`], [`animation`], [`body_part`], [`blueprint`], [`soldier`],
//!   [`horse`], [`character`]; LODs and their selection: [`lod`];
//! - correctness: [`validate`] (weights and bone indices), [`cpu_skinning`] (f64 reference);
//! - the crowd: [`steering`] (behaviour), [`culling`] (frustum culling and LOD choice);
//! - on the GPU: [`vertex_textures`] and [`bone_textures`] (Fig. 1), [`pass1_skinning`]
//!   (Fig. 2), [`render_to_vbo`], [`pass2_draw`], the baseline [`vertex_shader_skinning`],
//!   [`sprites`]; a frame of either method: [`renderer`]; the measured scenes: [`scene`].
//!
//! The commands `crowd` and `crowd-bench` live in the binary (`src/cli/crowd.rs`) and the
//! report (`report::paper2`); nothing here knows of them.

pub mod animation;
pub mod blueprint;
pub mod body_part;
pub mod bone_textures;
pub mod character;
pub mod compute;
pub mod cpu_skinning;
pub mod culling;
pub mod horse;
pub mod lod;
pub mod pass1_skinning;
pub mod pass2_draw;
pub mod render_to_vbo;
pub mod renderer;
pub mod scene;
pub mod skeleton;
pub mod soldier;
pub mod sprites;
pub mod steering;
pub mod validate;
pub mod vertex_shader_skinning;
pub mod vertex_textures;

pub use character::{CharacterModel, ModelKind};
pub use lod::{Level, LodPolicy, LOD_TRIANGLES};
pub use renderer::{CrowdRenderer, Method};
pub use validate::{SkinError, SkinnedMesh};
