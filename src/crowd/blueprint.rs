//! What a character model is made of before tessellation: its skeleton, its body parts and
//! its clip. The soldier and the horse each give one, and the model's LOD meshes are built
//! from it.

use super::animation::Clip;
use super::body_part::BodyPart;
use super::skeleton::Skeleton;

/// What a model is made of before tessellation.
#[derive(Clone, Debug)]
pub struct Blueprint {
    pub skeleton: Skeleton,
    pub parts: Vec<BodyPart>,
    pub clip: Clip,
}
