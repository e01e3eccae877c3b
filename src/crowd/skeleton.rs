//! The bone hierarchy of a skinned character and its posing (forward kinematics).
//!
//! Bones are given in the bind pose in model space (y up, the character faces +z). A bone
//! rotates about its head joint; its bind orientation is the identity, so the inverse bind
//! matrix is a translation by `-head`. Posing happens in f64 so that the CPU reference
//! skinning is exact to far below fp32; the GPU receives the same matrices rounded to f32.

use glam::{DAffine3, DQuat, DVec3};

use super::validate::SkinError;

/// One bone: where its joint sits in the bind pose, and where it ends.
#[derive(Clone, Debug, PartialEq)]
pub struct Bone {
    pub name: &'static str,
    /// Index of the parent bone; parents come before their children.
    pub parent: Option<usize>,
    /// The joint the bone rotates about, bind pose, model space.
    pub head: DVec3,
    /// The end of the bone, bind pose, model space (used for skin weights).
    pub tail: DVec3,
}

/// A bone hierarchy, parents before children.
#[derive(Clone, Debug, PartialEq)]
pub struct Skeleton {
    bones: Vec<Bone>,
}

/// The animated state of a skeleton: a local rotation per bone and a root offset.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    pub local_rotations: Vec<DQuat>,
    pub root_offset: DVec3,
}

impl Skeleton {
    /// Checks that every parent index points to an earlier bone and that there is one root.
    pub fn new(bones: Vec<Bone>) -> Result<Self, SkinError> {
        if bones.is_empty() {
            return Err(SkinError::EmptySkeleton);
        }
        for (i, bone) in bones.iter().enumerate() {
            match bone.parent {
                None if i != 0 => return Err(SkinError::SecondRoot { bone: i }),
                Some(p) if p >= i => {
                    return Err(SkinError::ParentAfterChild { bone: i, parent: p });
                }
                _ => {}
            }
        }
        Ok(Self { bones })
    }

    pub fn bones(&self) -> &[Bone] {
        &self.bones
    }

    pub fn len(&self) -> usize {
        self.bones.len()
    }

    pub fn is_empty(&self) -> bool {
        self.bones.is_empty()
    }

    /// Index of the bone called `name`.
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.bones.iter().position(|b| b.name == name)
    }

    /// The bind pose: no rotation, no offset.
    pub fn bind_pose(&self) -> Pose {
        Pose {
            local_rotations: vec![DQuat::IDENTITY; self.len()],
            root_offset: DVec3::ZERO,
        }
    }

    /// World (model-space) transform of every bone in `pose`: parent * T(joint offset) * R.
    pub fn world_transforms(&self, pose: &Pose) -> Vec<DAffine3> {
        let mut world: Vec<DAffine3> = Vec::with_capacity(self.len());
        for (i, bone) in self.bones.iter().enumerate() {
            let rotation = DAffine3::from_quat(pose.local_rotations[i]);
            let transform = match bone.parent {
                None => DAffine3::from_translation(bone.head + pose.root_offset) * rotation,
                Some(p) => {
                    let offset = bone.head - self.bones[p].head;
                    world[p] * DAffine3::from_translation(offset) * rotation
                }
            };
            world.push(transform);
        }
        world
    }

    /// The skinning matrices `model * world_j * bind_j^-1`: they take a bind-pose vertex
    /// straight to world coordinates, as pass 1 of the paper does.
    pub fn skinning_matrices(&self, pose: &Pose, model: DAffine3) -> Vec<DAffine3> {
        self.world_transforms(pose)
            .iter()
            .zip(&self.bones)
            .map(|(world, bone)| model * *world * DAffine3::from_translation(-bone.head))
            .collect()
    }
}
