//! The lecture-1 section's parts (minimal here: the full section comes with the other
//! lecture-1 techniques).

pub mod penetration;
