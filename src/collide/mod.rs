//! Paper 1: Zhang & Kim, "Interactive Collision Detection for Deformable Models using
//! Streaming AABBs", IEEE TVCG 13(2), 2007.
