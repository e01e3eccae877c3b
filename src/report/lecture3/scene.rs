//! The section's fixed views, which its measurements, pictures and tables share: the
//! displacement-mapped box and the camera looking at it, and the light hierarchy's criteria.

/// Box height of a white sample in the section's views.
pub const DEPTH: f32 = 0.3;
/// The camera's distance from the box centre.
pub const DISTANCE: f32 = 3.2;

/// The criteria of the error/speed plot.
pub const THETAS: [f32; 8] = [0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5];
