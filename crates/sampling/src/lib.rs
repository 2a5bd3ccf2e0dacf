//! CPU twins of `shaders/include/rng.glsl` (and, later, the other samplers). Every function
//! here has a GLSL function of the same name computing the same bits; GPU tests compare them.
//! All randomness is a pure function of (seed, sample index, dimension): no hidden state.

pub mod rng;
