//! The sites of a diagram and the SITES.json format:
//!
//! ```json
//! {"domain": {"min": [0, 0], "size": 10},
//!  "sites": [{"point": [1, 2]},
//!            {"segment": [[3, 1], [7, 2]]},
//!            {"triangle": [[2, 6], [4, 9], [1, 8]]}]}
//! ```
//!
//! `domain` (optional) is the square the `n x n` pixels cover, from `min` with side `size`;
//! without it, the sites' bounding box made square about its centre and grown by a tenth of
//! its side on every side. Site ids are positions in the list, from 0.

use anyhow::Context as _;
use glam::DVec2;
use serde::Deserialize;
use std::path::Path;

/// One site.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "lowercase", deny_unknown_fields)]
pub enum Site {
    Point([f64; 2]),
    Segment([[f64; 2]; 2]),
    Triangle([[f64; 2]; 3]),
}

impl Site {
    /// The site's corners.
    pub fn corners(&self) -> Vec<DVec2> {
        match self {
            Site::Point(p) => vec![DVec2::from(*p)],
            Site::Segment(s) => s.iter().map(|&p| DVec2::from(p)).collect(),
            Site::Triangle(t) => t.iter().map(|&p| DVec2::from(p)).collect(),
        }
    }

    /// The kind as the shaders number it: 0 point, 1 segment, 2 triangle.
    pub fn kind(&self) -> u32 {
        match self {
            Site::Point(_) => 0,
            Site::Segment(_) => 1,
            Site::Triangle(_) => 2,
        }
    }

    /// Distance from `p` (zero inside a triangle, its edges included).
    pub fn distance(&self, p: DVec2) -> f64 {
        match self {
            Site::Point(a) => (p - DVec2::from(*a)).length(),
            Site::Segment([a, b]) => segment(p, DVec2::from(*a), DVec2::from(*b)),
            Site::Triangle([a, b, c]) => {
                let (a, b, c) = (DVec2::from(*a), DVec2::from(*b), DVec2::from(*c));
                if inside(p, a, b, c) {
                    0.0
                } else {
                    segment(p, a, b).min(segment(p, b, c)).min(segment(p, c, a))
                }
            }
        }
    }
}

/// Distance from `p` to the segment `a b` (a point when `a == b`).
pub fn segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + t * ab)).length()
}

/// `p` inside the triangle or on its edges, either orientation; never for zero area.
fn inside(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    let area = (b - a).perp_dot(c - a);
    if area == 0.0 {
        return false;
    }
    let s = area.signum();
    s * (b - a).perp_dot(p - a) >= 0.0
        && s * (c - b).perp_dot(p - b) >= 0.0
        && s * (a - c).perp_dot(p - c) >= 0.0
}

/// The square the pixels cover.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Domain {
    pub min: [f64; 2],
    pub size: f64,
}

impl Domain {
    /// The side of one of `n x n` pixels.
    pub fn pixel(&self, n: usize) -> f64 {
        self.size / n as f64
    }

    /// The centre of pixel `(x, y)` (y from the bottom).
    pub fn centre(&self, n: usize, x: usize, y: usize) -> DVec2 {
        DVec2::from(self.min) + self.pixel(n) * DVec2::new(x as f64 + 0.5, y as f64 + 0.5)
    }
}

/// A SITES.json file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sites {
    #[serde(default)]
    pub domain: Option<Domain>,
    pub sites: Vec<Site>,
}

impl Sites {
    pub fn load(path: &Path) -> anyhow::Result<Sites> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("reading the sites {}", path.display()))?;
        Sites::parse(&text).with_context(|| format!("the sites {}", path.display()))
    }

    /// Parse and check: at least one site, every coordinate finite, a positive square domain.
    pub fn parse(text: &str) -> anyhow::Result<Sites> {
        let sites: Sites = serde_json::from_str(text).context(
            "expected {\"sites\": [{\"point\": [x, y]} | {\"segment\": [[x, y], [x, y]]} | \
             {\"triangle\": [[x, y], [x, y], [x, y]]}, ...], \"domain\": {\"min\": [x, y], \
             \"size\": s} (optional)}",
        )?;
        sites.check()?;
        Ok(sites)
    }

    fn check(&self) -> anyhow::Result<()> {
        anyhow::ensure!(!self.sites.is_empty(), "no site given");
        anyhow::ensure!(
            self.sites.len() < 1 << 24,
            "{} sites: site ids travel as floats, exact below 2^24",
            self.sites.len()
        );
        for (i, s) in self.sites.iter().enumerate() {
            if s.corners().iter().any(|c| !c.is_finite()) {
                anyhow::bail!("site {i} has a coordinate that is not finite");
            }
        }
        if let Some(d) = self.domain {
            anyhow::ensure!(
                d.min.iter().all(|v| v.is_finite()) && d.size.is_finite() && d.size > 0.0,
                "the domain must have a finite min and a positive, finite size"
            );
        }
        Ok(())
    }

    /// The given domain, or the default one (see the module doc).
    pub fn domain(&self) -> anyhow::Result<Domain> {
        if let Some(d) = self.domain {
            return Ok(d);
        }
        let corners: Vec<DVec2> = self.sites.iter().flat_map(|s| s.corners()).collect();
        let lo = corners.iter().copied().fold(DVec2::INFINITY, DVec2::min);
        let hi = corners
            .iter()
            .copied()
            .fold(DVec2::NEG_INFINITY, DVec2::max);
        let side = (hi - lo).max_element();
        let side = if side > 0.0 { side } else { 1.0 };
        let size = side * 1.2;
        let centre = (lo + hi) * 0.5;
        let domain = Domain {
            min: (centre - DVec2::splat(size * 0.5)).to_array(),
            size,
        };
        anyhow::ensure!(
            domain.min.iter().all(|v| v.is_finite()) && size.is_finite(),
            "the sites' bounding box is too large for a finite domain"
        );
        Ok(domain)
    }
}
