//! Stream setup [Sec. 4.1]: a top-down AABB tree per model, pulled down into a complete
//! binary tree whose leaf level, virtual nodes included, is the AABB stream `S^X`.
//!
//! The tree is built once, as a preprocess, and never rebuilt: deformation only moves the
//! vertices, and the stream update (Sec. 6) refits the leaf boxes on the GPU.

use super::aabb::Aabb;
use super::CollideError;
use crate::mesh::Mesh;
use glam::Vec3;

/// Default leaf size `n` (triangles per leaf), chosen by measurement (`collide-bench`'s
/// leaf-size sweep on the 15K-triangle interlocking tori, llvmpipe on 2 cores): halving `n`
/// doubles both streams and so makes `P0` four times larger (n = 8 gives the paper's
/// 2048 x 2048 `P0`: 79 ms per frame; n = 16: 19 ms; n = 32: 5 ms), while doubling it roughly
/// doubles the PCTPs of the CPU triangle test (n = 64: 4 ms, but 2.5x the PCTPs of n = 32,
/// which contact-heavy frames pay). A GPU with fast fragment rates favours smaller leaves;
/// `--leaf-size` sets it.
pub const DEFAULT_LEAF_SIZE: usize = 32;

/// The most stream slots the automatic leaf size allows per model on a software renderer:
/// 512, the `P0` side of the 15K-triangle tori at [`DEFAULT_LEAF_SIZE`]. There every `P0`
/// pixel is CPU time (a 2048 x 2048 `P0` costs 16 times a 512 x 512 one), so larger models
/// get larger leaves instead of a larger `P0`.
pub const SOFTWARE_MAX_SLOTS: usize = 512;

/// The same bound on a GPU: 4096, the largest `P0` side the paper considers. Fragments are
/// cheap there and larger leaves only add CPU triangle tests (measured on an H100: the 20K
/// scene took 37 ms at n = 64 against 8 ms at n = 32).
pub const HARDWARE_MAX_SLOTS: usize = 4096;

/// The slot bound for a renderer.
pub fn max_slots(software_renderer: bool) -> usize {
    if software_renderer {
        SOFTWARE_MAX_SLOTS
    } else {
        HARDWARE_MAX_SLOTS
    }
}

/// The leaf size for `mesh`: [`DEFAULT_LEAF_SIZE`], doubled until the stream has at most
/// `max_slots` slots.
pub fn auto_leaf_size(mesh: &Mesh, max_slots: usize) -> Result<usize, CollideError> {
    let mut n = DEFAULT_LEAF_SIZE;
    while AabbStream::build(mesh, n)?.len() > max_slots && n < mesh.triangles.len() {
        n *= 2;
    }
    Ok(n)
}

/// The automatic leaf size of a pair of models on a renderer: the larger of the two models'
/// [`auto_leaf_size`], so both streams stay within the bound.
pub fn auto_leaf_size_for_pair(
    x: &Mesh,
    y: &Mesh,
    software_renderer: bool,
) -> Result<usize, CollideError> {
    let slots = max_slots(software_renderer);
    Ok(auto_leaf_size(x, slots)?.max(auto_leaf_size(y, slots)?))
}

/// One real leaf of the AABB tree: a group of triangles and the unique vertices they use.
#[derive(Clone, Debug, PartialEq)]
pub struct Leaf {
    /// Triangle indices into the model's triangle list.
    pub triangles: Vec<u32>,
    /// The unique vertices of those triangles (the leaf's "vertex list", Sec. 4.1), sorted.
    pub vertices: Vec<u32>,
    /// Depth of the leaf in the original (not yet pulled down) tree; the root is 0.
    pub depth: u32,
}

/// A node of the original top-down tree, as SOLID keeps it (used by the SOLID baseline).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TreeNode {
    /// Indices of the two children in [`AabbStream::tree`].
    Internal([u32; 2]),
    /// Index into [`AabbStream::leaves`].
    Leaf(u32),
}

/// The AABB stream `S^X` of one model: the leaf level of the complete binary tree.
#[derive(Clone, Debug)]
pub struct AabbStream {
    /// `d_max`: the height of the complete binary tree; the stream has `2^d_max` slots.
    pub depth: u32,
    /// The real leaves, left to right.
    pub leaves: Vec<Leaf>,
    /// For each of the `2^d_max` slots, the real leaf it holds. A leaf pulled down by `k`
    /// levels fills `2^k` consecutive slots: itself and its virtual copies.
    pub slot_leaf: Vec<u32>,
    /// The stencil array [Sec. 4.2.1]: 1 for the first slot of each real leaf, 0 for its
    /// virtual copies. With one pulled-down level this is exactly the paper's rule ("the
    /// first virtual node of two siblings is one, the second zero"); with deeper pull-downs
    /// it keeps one representative per leaf, so no leaf pair is ever reported twice.
    pub stencil: Vec<u8>,
    /// `n_max`: the largest number of unique vertices in one leaf (rows of the vertex texture).
    pub n_max: usize,
    /// The original tree (root first, children after parents), for the SOLID baseline.
    pub tree: Vec<TreeNode>,
    /// The leaf size `n` it was built with.
    pub leaf_size: usize,
}

impl AabbStream {
    /// Build the stream of `mesh` with at most `leaf_size` triangles per leaf.
    pub fn build(mesh: &Mesh, leaf_size: usize) -> Result<AabbStream, CollideError> {
        validate_mesh(mesh)?;
        if leaf_size == 0 {
            return Err(CollideError::BadInput(
                "leaf size must be at least 1".into(),
            ));
        }
        let centroids: Vec<Vec3> = (0..mesh.triangles.len())
            .map(|t| {
                let [a, b, c] = mesh.triangle(t);
                (a + b + c) / 3.0
            })
            .collect();
        let mut builder = TreeBuilder {
            mesh,
            centroids: &centroids,
            leaf_size,
            leaves: Vec::new(),
            tree: Vec::new(),
        };
        let mut all: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
        builder.split(&mut all, 0);
        let TreeBuilder { leaves, tree, .. } = builder;
        Ok(pull_down(leaves, tree, leaf_size))
    }

    /// Number of slots, `2^d_max`.
    pub fn len(&self) -> usize {
        self.slot_leaf.len()
    }

    pub fn is_empty(&self) -> bool {
        self.slot_leaf.is_empty()
    }

    /// Number of virtual slots (copies of a pulled-down leaf).
    pub fn virtual_slots(&self) -> usize {
        self.len() - self.leaves.len()
    }

    /// CPU reference of the leaf boxes for the given (possibly deformed) positions.
    pub fn leaf_boxes(&self, positions: &[Vec3]) -> Vec<Aabb> {
        self.leaves
            .iter()
            .map(|leaf| Aabb::from_points(leaf.vertices.iter().map(|&v| positions[v as usize])))
            .collect()
    }

    /// CPU reference of `T_min`/`T_max` [Eq. 1]: one box per slot, virtual slots copying
    /// their real leaf.
    pub fn slot_boxes(&self, positions: &[Vec3]) -> Vec<Aabb> {
        let leaf_boxes = self.leaf_boxes(positions);
        self.slot_leaf
            .iter()
            .map(|&l| leaf_boxes[l as usize])
            .collect()
    }
}

/// Reject what the pipeline cannot handle, naming the problem.
pub fn validate_mesh(mesh: &Mesh) -> Result<(), CollideError> {
    if mesh.triangles.is_empty() {
        return Err(CollideError::BadInput("the mesh has no triangles".into()));
    }
    if let Some(i) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(CollideError::BadInput(format!(
            "vertex {i} has a non-finite coordinate {:?}",
            mesh.positions[i]
        )));
    }
    let n = mesh.positions.len();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if let Some(&v) = tri.iter().find(|&&v| v as usize >= n) {
            return Err(CollideError::BadInput(format!(
                "triangle {t} uses vertex {v}, but the mesh has only {n} vertices"
            )));
        }
    }
    Ok(())
}

struct TreeBuilder<'a> {
    mesh: &'a Mesh,
    centroids: &'a [Vec3],
    leaf_size: usize,
    leaves: Vec<Leaf>,
    tree: Vec<TreeNode>,
}

impl TreeBuilder<'_> {
    /// Top-down subdivision as in SOLID (the paper's reference 2): split the triangles at the median centroid along the
    /// longest axis of their centroids' box, until a group has at most `n` triangles.
    /// The median keeps the tree balanced, so few virtual nodes are needed.
    fn split(&mut self, triangles: &mut [u32], depth: u32) -> u32 {
        let node = self.tree.len() as u32;
        self.tree.push(TreeNode::Leaf(0));
        if triangles.len() <= self.leaf_size {
            self.tree[node as usize] = TreeNode::Leaf(self.leaves.len() as u32);
            self.leaves.push(self.make_leaf(triangles, depth));
            return node;
        }
        let bounds = Aabb::from_points(triangles.iter().map(|&t| self.centroids[t as usize]));
        let axis = bounds.longest_axis();
        let mid = triangles.len() / 2;
        let key = |t: &u32| self.centroids[*t as usize][axis];
        triangles.select_nth_unstable_by(mid, |a, b| key(a).total_cmp(&key(b)));
        let (left, right) = triangles.split_at_mut(mid);
        let l = self.split(left, depth + 1);
        let r = self.split(right, depth + 1);
        self.tree[node as usize] = TreeNode::Internal([l, r]);
        node
    }

    fn make_leaf(&self, triangles: &[u32], depth: u32) -> Leaf {
        let mut triangles = triangles.to_vec();
        triangles.sort_unstable();
        let mut vertices: Vec<u32> = triangles
            .iter()
            .flat_map(|&t| self.mesh.triangles[t as usize])
            .collect();
        vertices.sort_unstable();
        vertices.dedup();
        Leaf {
            triangles,
            vertices,
            depth,
        }
    }
}

/// Pulling down [Fig. 3]: every leaf above the bottom level gets virtual children, copies
/// of itself, down to `d_max`. Leaves come out of the depth-first build left to right, so
/// the slots of one leaf are consecutive.
fn pull_down(leaves: Vec<Leaf>, tree: Vec<TreeNode>, leaf_size: usize) -> AabbStream {
    let depth = leaves.iter().map(|l| l.depth).max().unwrap_or(0);
    let mut slot_leaf = Vec::with_capacity(1 << depth);
    let mut stencil = Vec::with_capacity(1 << depth);
    for (i, leaf) in leaves.iter().enumerate() {
        let copies = 1usize << (depth - leaf.depth);
        for k in 0..copies {
            slot_leaf.push(i as u32);
            stencil.push(u8::from(k == 0));
        }
    }
    debug_assert_eq!(slot_leaf.len(), 1 << depth);
    let n_max = leaves.iter().map(|l| l.vertices.len()).max().unwrap_or(0);
    AabbStream {
        depth,
        leaves,
        slot_leaf,
        stencil,
        n_max,
        tree,
        leaf_size,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strip(n: usize) -> Mesh {
        // A strip of n triangles along x.
        let mut positions = Vec::new();
        for i in 0..=n / 2 + 1 {
            positions.push(Vec3::new(i as f32, 0.0, 0.0));
            positions.push(Vec3::new(i as f32, 1.0, 0.0));
        }
        let triangles = (0..n as u32)
            .map(|t| {
                let b = (t / 2) * 2;
                if t % 2 == 0 {
                    [b, b + 2, b + 1]
                } else {
                    [b + 1, b + 2, b + 3]
                }
            })
            .collect();
        Mesh::new(positions, triangles)
    }

    #[test]
    fn every_triangle_is_in_exactly_one_leaf_of_at_most_n() {
        for n in [1, 2, 3, 7] {
            let mesh = strip(37);
            let s = AabbStream::build(&mesh, n).unwrap();
            let mut seen = [0; 37];
            for leaf in &s.leaves {
                assert!(leaf.triangles.len() <= n && !leaf.triangles.is_empty());
                for &t in &leaf.triangles {
                    seen[t as usize] += 1;
                }
            }
            assert!(seen.iter().all(|&c| c == 1));
            assert_eq!(s.len(), 1 << s.depth);
        }
    }

    #[test]
    fn pulled_down_leaves_have_one_stencil_representative() {
        let s = AabbStream::build(&strip(37), 4).unwrap();
        assert!(
            s.virtual_slots() > 0,
            "37 triangles in leaves of 4 need virtual nodes"
        );
        for leaf in 0..s.leaves.len() as u32 {
            let marked: u32 = (0..s.len())
                .filter(|&k| s.slot_leaf[k] == leaf)
                .map(|k| s.stencil[k] as u32)
                .sum();
            assert_eq!(marked, 1);
        }
        // The paper's rule for one pulled-down level: first virtual sibling 1, second 0.
        for k in 0..s.len() - 1 {
            let l = s.slot_leaf[k] as usize;
            if s.depth - s.leaves[l].depth == 1 && (k == 0 || s.slot_leaf[k - 1] as usize != l) {
                assert_eq!((s.stencil[k], s.stencil[k + 1]), (1, 0));
            }
        }
    }

    #[test]
    fn bad_meshes_are_rejected_with_a_reason() {
        let empty = Mesh::default();
        assert!(AabbStream::build(&empty, 4)
            .unwrap_err()
            .to_string()
            .contains("no triangles"));
        let mut nan = strip(4);
        nan.positions[2].y = f32::NAN;
        assert!(AabbStream::build(&nan, 4)
            .unwrap_err()
            .to_string()
            .contains("vertex 2"));
        let mut bad_index = strip(4);
        bad_index.triangles[1][0] = 999;
        assert!(AabbStream::build(&bad_index, 4)
            .unwrap_err()
            .to_string()
            .contains("triangle 1"));
    }
}
