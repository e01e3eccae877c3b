//! The page layer: what every page and folder the program writes is made with, under the
//! papers' report ([`crate::report`]), the course's guide ([`crate::learn::guide`]) and the
//! `compare` page ([`crate::compare`]).
//!
//! - [`html`]: escaping and the one style sheet;
//! - [`plot`]: line plots as PNG, made to be read without the code;
//! - [`folder`]: the folder writer, one rule for every command that writes a folder (a marker
//!   listing its files, a staging folder swapped in at the end, nothing of the user's removed).
//!
//! It knows nothing of papers, claims or lessons: pictures of GL buffers are the GL layer's
//! ([`crate::gl::picture`]), and what a page says is its room's.

pub mod folder;
pub mod html;
pub mod plot;
