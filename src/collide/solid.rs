//! The SOLID baseline (the paper's reference 2; Sec. 7.4.1): the same leaves kept in a
//! CPU AABB tree, refitted bottom-up every frame (SOLID's scheme for deformable models: new leaf boxes from the
//! vertices, then each internal box as the union of its children's), and traversed as a
//! tree pair to find the overlapping leaves. The triangle test is the pipeline's own.

use super::aabb::Aabb;
use super::stream_setup::{AabbStream, TreeNode};
use glam::Vec3;

/// Refit the tree of `stream` to `positions`: one box per tree node.
pub fn refit(stream: &AabbStream, positions: &[Vec3]) -> Vec<Aabb> {
    let mut boxes = vec![Aabb::EMPTY; stream.tree.len()];
    // Children are stored after their parent, so a reverse sweep is bottom-up.
    for (i, node) in stream.tree.iter().enumerate().rev() {
        boxes[i] = match *node {
            TreeNode::Leaf(l) => Aabb::from_points(
                stream.leaves[l as usize]
                    .vertices
                    .iter()
                    .map(|&v| positions[v as usize]),
            ),
            TreeNode::Internal([a, b]) => boxes[a as usize].union(boxes[b as usize]),
        };
    }
    boxes
}

/// Simultaneous descent of two refitted trees; returns the overlapping leaf pairs
/// `(leaf of X, leaf of Y)`, sorted. The node with the larger box is split first.
pub fn overlapping_leaves(
    x: &AabbStream,
    boxes_x: &[Aabb],
    y: &AabbStream,
    boxes_y: &[Aabb],
) -> Vec<(u32, u32)> {
    let mut caps = Vec::new();
    let mut stack = vec![(0u32, 0u32)];
    while let Some((a, b)) = stack.pop() {
        if !boxes_x[a as usize].overlaps(&boxes_y[b as usize]) {
            continue;
        }
        match (x.tree[a as usize], y.tree[b as usize]) {
            (TreeNode::Leaf(la), TreeNode::Leaf(lb)) => caps.push((la, lb)),
            (TreeNode::Internal([a0, a1]), TreeNode::Leaf(_)) => {
                stack.extend([(a0, b), (a1, b)]);
            }
            (TreeNode::Leaf(_), TreeNode::Internal([b0, b1])) => {
                stack.extend([(a, b0), (a, b1)]);
            }
            (TreeNode::Internal([a0, a1]), TreeNode::Internal([b0, b1])) => {
                if boxes_x[a as usize].volume() >= boxes_y[b as usize].volume() {
                    stack.extend([(a0, b), (a1, b)]);
                } else {
                    stack.extend([(a, b0), (a, b1)]);
                }
            }
        }
    }
    caps.sort_unstable();
    caps
}

/// All pairs of real leaves whose boxes overlap, by testing every pair: the CPU reference
/// for the streaming AABB test and for the tree traversal.
pub fn all_overlapping_leaves(boxes_x: &[Aabb], boxes_y: &[Aabb]) -> Vec<(u32, u32)> {
    let mut caps = Vec::new();
    for (a, bx) in boxes_x.iter().enumerate() {
        for (b, by) in boxes_y.iter().enumerate() {
            if bx.overlaps(by) {
                caps.push((a as u32, b as u32));
            }
        }
    }
    caps
}
