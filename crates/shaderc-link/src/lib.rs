//! shaderc, linked statically against the Debian 12 archives (see build.rs).
pub use shaderc::*;
