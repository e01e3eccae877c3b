//! What a traced pixel shows, on the CPU, as `write_hit` in `displace_common.glsl` computes
//! it: the normal (of the bilinear patch hit, or of the box side the ray came through), the
//! albedo (a checkerboard of 8x8 patches) and the colour under one directional light. The
//! comparison with the exact tracer ([`super::compare`]) judges these per pixel, not only
//! where the ray stops.

use super::surface::Surface;
use glam::DVec3;

/// The light's direction (towards the light), as in the shader.
pub fn light() -> DVec3 {
    DVec3::new(0.4, 0.3, 0.85).normalize()
}

/// The two albedos of the checkerboard.
pub const ALBEDO_EVEN: [f64; 3] = [0.85, 0.75, 0.6];
pub const ALBEDO_ODD: [f64; 3] = [0.55, 0.6, 0.75];
/// Patches per checkerboard square.
pub const SQUARE: f64 = 8.0;

/// The world-space normal of patch `cell` of `surface` at local coordinates `st`.
pub fn patch_normal(surface: &Surface, cell: (u32, u32), st: (f64, f64)) -> DVec3 {
    let h = surface.corners(cell.0, cell.1, 0.0);
    let c = h[0] - h[1] - h[2] + h[3];
    let dhds = (h[1] - h[0]) + c * st.1;
    let dhdt = (h[2] - h[0]) + c * st.0;
    // World slopes: dz/dx = (dH/ds) (grid x per world x) / (grid z per world z).
    let scale = surface.world_to_grid().as_dvec3();
    let slope = (dhds * scale.x / scale.z, dhdt * scale.y / scale.z);
    DVec3::new(-slope.0, -slope.1, 1.0).normalize()
}

/// The normal of the map's field at grid `g` (the patch containing it, clamped to the map),
/// as `write_hit` takes it.
pub fn field_normal(surface: &Surface, g: DVec3) -> DVec3 {
    let (wp, hp) = surface.patches();
    let cell = (
        (g.x.floor().max(0.0) as u32).min(wp - 1),
        (g.y.floor().max(0.0) as u32).min(hp - 1),
    );
    patch_normal(surface, cell, (g.x - cell.0 as f64, g.y - cell.1 as f64))
}

/// The normals a surface point at grid `g` may be shown with: its patch's, and where `g`
/// lies within `margin` patches of a patch edge, the neighbours' (the field's normal jumps
/// across patch edges, so a hit rounded onto the other side shows the neighbour's).
pub fn surface_normals(surface: &Surface, g: DVec3, margin: f64) -> Vec<DVec3> {
    let (wp, hp) = surface.patches();
    let cells = |x: f64, n: u32| {
        let lo = ((x - margin).floor().max(0.0) as u32).min(n - 1);
        let hi = ((x + margin).floor().max(0.0) as u32).min(n - 1);
        lo..=hi
    };
    let mut normals = Vec::new();
    for j in cells(g.y, hp) {
        for i in cells(g.x, wp) {
            let st = (
                (g.x - i as f64).clamp(0.0, 1.0),
                (g.y - j as f64).clamp(0.0, 1.0),
            );
            normals.push(patch_normal(surface, (i, j), st));
        }
    }
    normals
}

/// The box's four sides as seen from grid `g`: (distance from `g` to the side's plane, its
/// outward normal), in the shader's order (-x, +x, -y, +y).
fn sides(surface: &Surface, g: DVec3) -> [(f64, DVec3); 4] {
    let (wp, hp) = surface.patches();
    [
        (g.x, DVec3::NEG_X),
        (wp as f64 - g.x, DVec3::X),
        (g.y, DVec3::NEG_Y),
        (hp as f64 - g.y, DVec3::Y),
    ]
}

/// The outward normals of the box sides within `margin` patches of grid `g` (a wall hit lies
/// on one side; near a vertical edge of the box, either side may be shown).
pub fn wall_normals(surface: &Surface, g: DVec3, margin: f64) -> Vec<DVec3> {
    sides(surface, g)
        .into_iter()
        .filter(|(distance, _)| distance.abs() <= margin)
        .map(|(_, n)| n)
        .collect()
}

/// The outward normal of the box side nearest grid `g` (where a wall hit lies), as the shader
/// picks it (ties: the first in its order).
pub fn wall_normal(surface: &Surface, g: DVec3) -> DVec3 {
    sides(surface, g)
        .into_iter()
        .fold((f64::INFINITY, DVec3::NEG_X), |best, (d, n)| {
            if d < best.0 {
                (d, n)
            } else {
                best
            }
        })
        .1
}

/// The checkerboard's albedo at grid `g`.
pub fn albedo(g: DVec3) -> [f64; 3] {
    albedos(g, 0.0)[0]
}

/// The albedos a point at grid `g` may be shown with: its square's, and both where `g` lies
/// within `margin` patches of a square's edge.
pub fn albedos(g: DVec3, margin: f64) -> Vec<[f64; 3]> {
    let parity = |x: f64, y: f64| ((x / SQUARE).floor() as i64 + (y / SQUARE).floor() as i64) & 1;
    let mut found = Vec::new();
    for (dx, dy) in [(0.0, 0.0), (-1.0, 0.0), (1.0, 0.0), (0.0, -1.0), (0.0, 1.0)] {
        let p = parity(g.x + dx * margin, g.y + dy * margin);
        let albedo = if p == 0 { ALBEDO_EVEN } else { ALBEDO_ODD };
        if !found.contains(&albedo) {
            found.push(albedo);
        }
    }
    found
}

/// The colour (RGB in [0, 1]) of a point with `albedo` and `normal`.
pub fn shade(albedo: [f64; 3], normal: DVec3) -> [f64; 3] {
    let lit = 0.25 + 0.75 * normal.dot(light()).max(0.0);
    albedo.map(|a| a * lit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lecture3::HeightMap;

    #[test]
    fn a_flat_patch_faces_up_and_a_ramp_leans_away_from_its_rise() {
        let map = HeightMap::new("ramp", 3, 2, vec![0.5, 0.5, 1.0, 0.5, 0.5, 1.0]).unwrap();
        let surface = Surface::new(map, 0.5).unwrap();
        assert!((patch_normal(&surface, (0, 0), (0.5, 0.5)) - DVec3::Z).length() < 1e-12);
        let ramp = patch_normal(&surface, (1, 0), (0.5, 0.5));
        assert!(
            ramp.x < -0.1 && ramp.y.abs() < 1e-12 && ramp.z > 0.0,
            "{ramp}"
        );
        // On the edge between them both are allowed; away from it only one.
        assert_eq!(
            surface_normals(&surface, DVec3::new(1.0, 0.5, 0.5), 1e-3).len(),
            2
        );
        assert_eq!(
            surface_normals(&surface, DVec3::new(0.5, 0.5, 0.5), 1e-3).len(),
            1
        );
        assert_eq!(albedos(DVec3::new(8.0, 3.0, 0.0), 1e-3).len(), 2);
        assert_eq!(albedos(DVec3::new(7.0, 3.0, 0.0), 1e-3), vec![ALBEDO_EVEN]);
        assert_eq!(albedos(DVec3::new(9.0, 3.0, 0.0), 1e-3), vec![ALBEDO_ODD]);
    }
}
