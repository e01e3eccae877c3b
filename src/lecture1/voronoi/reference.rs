//! The CPU reference: every pixel against every site in f64, the smallest id among equal
//! distances; and the comparison of a diagram with it.

use super::{Diagram, Domain, Site};
use serde::Serialize;

/// The diagram by brute force.
pub fn brute_force(sites: &[Site], domain: Domain, n: usize, depth_range: f64) -> Diagram {
    let mut site = Vec::with_capacity(n * n);
    let mut distance = Vec::with_capacity(n * n);
    for y in 0..n {
        for x in 0..n {
            let (s, d) = nearest(sites, domain.centre(n, x, y));
            site.push(s);
            distance.push(d as f32);
        }
    }
    Diagram {
        n,
        domain,
        site,
        distance,
        depth_range,
        mesh_error: 0.0,
        coverage_error: 0.0,
    }
}

/// The nearest site to `p` (the smallest id on a tie) and its distance.
pub fn nearest(sites: &[Site], p: glam::DVec2) -> (u32, f64) {
    let mut best = (0, f64::INFINITY);
    for (i, s) in sites.iter().enumerate() {
        let d = s.distance(p);
        if d < best.1 {
            best = (i as u32, d);
        }
    }
    best
}

/// How a diagram agrees with the reference.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Agreement {
    pub pixels: usize,
    /// Pixels given the same site.
    pub same_site: usize,
    /// Pixels given another site whose distance equals the nearest one's within the
    /// tolerance (a tie).
    pub ties: usize,
    /// Pixels given a site farther than the nearest by more than the tolerance.
    pub wrong: usize,
    /// The largest difference between a pixel's distance and the reference's, input units.
    pub max_distance_error: f64,
    /// The tolerance of a tie and of a distance (input units), [`Diagram::tolerance`].
    pub tolerance: f64,
}

impl Agreement {
    /// Every pixel the right site (up to ties) at the right distance.
    pub fn agrees(&self) -> bool {
        self.wrong == 0 && self.max_distance_error <= self.tolerance
    }
}

/// Compare `diagram` with brute force on `sites`.
pub fn compare(diagram: &Diagram, sites: &[Site]) -> Agreement {
    let n = diagram.n;
    let tolerance = diagram.tolerance();
    let mut a = Agreement {
        pixels: n * n,
        tolerance,
        ..Agreement::default()
    };
    for y in 0..n {
        for x in 0..n {
            let i = y * n + x;
            let p = diagram.domain.centre(n, x, y);
            let (s, d) = nearest(sites, p);
            let given = diagram.site[i];
            if given == s {
                a.same_site += 1;
            } else if (given as usize) < sites.len()
                && sites[given as usize].distance(p) - d <= tolerance
            {
                a.ties += 1;
            } else {
                a.wrong += 1;
            }
            a.max_distance_error = a
                .max_distance_error
                .max((diagram.distance[i] as f64 - d).abs());
        }
    }
    a
}
