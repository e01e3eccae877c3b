//! Fig. 1-(b): the bone matrices of every character, computed on the CPU each frame, as
//! three textures holding one row each of the 3x4 matrices. Texel (bone, character).

use glam::DAffine3;

use crate::gl::{Context, GlError, Texture, TextureFormat};

/// Row `r` of a 3x4 affine matrix: `[m_r0, m_r1, m_r2, t_r]`.
pub fn matrix_row(m: &DAffine3, r: usize) -> [f32; 4] {
    [
        m.matrix3.x_axis[r] as f32,
        m.matrix3.y_axis[r] as f32,
        m.matrix3.z_axis[r] as f32,
        m.translation[r] as f32,
    ]
}

/// The three row arrays for characters' skinning matrices (`bones` per character, in
/// character order): row `r` of bone `b` of character `c` at texel `c * bones + b`.
pub fn pack_rows(matrices: &[DAffine3]) -> [Vec<f32>; 3] {
    [0, 1, 2].map(|r| matrices.iter().flat_map(|m| matrix_row(m, r)).collect())
}

/// Three RGBA32F textures of `bones x capacity` texels, rewritten every frame.
pub struct BoneTextures {
    pub rows: [Texture; 3],
    pub bones: u32,
    pub capacity: u32,
}

impl BoneTextures {
    pub fn new(ctx: &Context, bones: u32, capacity: u32) -> Result<Self, GlError> {
        let row = || Texture::new_2d(ctx, bones, capacity, TextureFormat::Rgba32F);
        Ok(Self {
            rows: [row()?, row()?, row()?],
            bones,
            capacity,
        })
    }

    /// Uploads the matrices of `matrices.len() / bones` characters into rows 0.. of the
    /// textures.
    pub fn upload(&self, matrices: &[DAffine3]) -> Result<(), GlError> {
        let characters = matrices.len() as u32 / self.bones;
        if characters > self.capacity || !(matrices.len() as u32).is_multiple_of(self.bones) {
            return Err(GlError::Invalid(format!(
                "{} bone matrices do not fill whole characters of {} bones within {}",
                matrices.len(),
                self.bones,
                self.capacity
            )));
        }
        if characters == 0 {
            return Ok(());
        }
        // region: bone-textures
        for (texture, data) in self.rows.iter().zip(pack_rows(matrices)) {
            texture.upload_region_f32(0, 0, self.bones, characters, &data)?;
        }
        // endregion
        Ok(())
    }
}
