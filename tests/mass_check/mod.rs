//! The comparison the mass tests share: ten volume integrals against a reference, each
//! within a fraction of the reference's largest (the integrals differ in scale by orders).
#![allow(dead_code)]

use classic_gpgpu::mass::VolumeIntegrals;

/// The largest magnitude of the ten integrals.
pub fn largest(i: &VolumeIntegrals) -> f64 {
    i.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// Every value of `got` (moved to `want`'s origin) within `rel` of the largest of `want`.
pub fn assert_integrals_close(what: &str, got: &VolumeIntegrals, want: &VolumeIntegrals, rel: f64) {
    let got = got.about(want.origin);
    let scale = largest(want);
    for (k, (g, w)) in got.to_array().iter().zip(want.to_array()).enumerate() {
        assert!(
            (g - w).abs() <= rel * scale,
            "{what}: integral {k}: got {g}, want {w} (scale {scale})\n{got:?}\n{want:?}"
        );
    }
}
