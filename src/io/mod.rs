//! Files: TOML cut specs, bundled presets, GemCad designs (`.asc` text and `.gem` binary),
//! meshes (OBJ/STL, glTF scenes), and safe (atomic) writing of outputs.

pub mod asc;
pub mod exact;
pub mod gem;
pub mod gif;
pub mod gltf;
pub mod guard;
pub mod hdr;
pub mod mesh;
pub mod png;
pub mod presets;
pub mod recipe;
pub mod spec;
pub mod text;

mod cut_file;
mod files;

pub use cut_file::{load_cut, parse_cut, write_cut, CUT_FORMATS};
pub use files::{check_writable, line_of, read_bytes, write_atomic};
