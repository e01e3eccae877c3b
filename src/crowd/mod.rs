//! Paper 2: Kang & Han, "Real-Time Animation of Large Crowds", ICEC 2006 (LNCS 4161).
//!
//! Skinning of large crowds in a pixel shader [section 2, Fig. 1-2]: vertex data and
//! per-frame bone matrices live in float textures; one draw call over a render target of
//! n characters x m vertices skins every vertex of every character (pass 1); the target
//! is copied into a vertex buffer through a pixel buffer object (render-to-VBO); pass 2
//! draws every character from that buffer with a shared index buffer. Section 3 adds
//! three LOD meshes (1,084, 544, 312 polygons), sprites and view-frustum culling, and
//! compares with skinning in the vertex shader (Table 1).
//!
//! The paper's notation is kept: n characters, m vertices per character, a 3x4 bone
//! matrix stored as three rows. One file per step:
//!
//! - characters: [`skeleton`], [`animation`], [`body_part`], [`soldier`], [`horse`],
//!   [`character`]; LODs and their selection: [`lod`];
//! - correctness: [`validate`] (weights and bone indices), [`cpu_skinning`] (f64 reference);
//! - the crowd: [`steering`] (behaviour), [`culling`] (frustum culling and LOD choice);
//! - on the GPU: [`vertex_textures`] and [`bone_textures`] (Fig. 1), [`pass1_skinning`]
//!   (Fig. 2), [`render_to_vbo`], [`pass2_draw`], the baseline [`vertex_shader_skinning`],
//!   [`sprites`]; a frame of either method: [`renderer`]; the measured scenes: [`scene`];
//!   the commands: [`cli`].

pub mod animation;
pub mod body_part;
pub mod bone_textures;
pub mod character;
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
