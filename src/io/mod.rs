//! Files in and out: triangle meshes (OBJ, STL) and the SVG facet diagram.

pub mod mesh;
pub mod svg;
