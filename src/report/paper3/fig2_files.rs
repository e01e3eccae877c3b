//! Fig. 2's two pictures, the photograph (a) and the detected mask (b): written into the
//! output folder by the bench, shown by the figure and named by the period block.

pub const FIG2A_FILE: &str = "paper3_fig2a_text.png";
pub const FIG2B_FILE: &str = "paper3_fig2b_mask.png";
