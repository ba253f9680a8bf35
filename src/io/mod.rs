//! Reading and writing cut files: GemCad `.asc` designs (more formats join here).
pub mod asc;
