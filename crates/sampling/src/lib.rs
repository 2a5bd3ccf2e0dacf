//! CPU twins of the GLSL samplers in `shaders/include/` (rng.glsl, sampling.glsl). Every
//! function here has a GLSL function of the same name computing the same bits; GPU tests
//! compare them. All randomness is a pure function of (seed, sample index, dimension).

pub mod hbo19;
pub mod r2;
pub mod rng;
pub mod sobol;

/// The per-pixel sampler, chosen at run time (the value is what the shader receives).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum Sampler {
    /// Independent hash per (seed, index, dimension).
    White = 0,
    /// Owen-scrambled Sobol (Burley 2020).
    Sobol = 1,
    /// R2 with a per-seed Cranley-Patterson rotation.
    R2 = 2,
    /// Owen-Sobol with per-pixel keys from an optimised tile (HBO+19, see [`hbo19`]); the seed
    /// is the tile position whose keys the pixel uses. Without a key table: plain Owen-Sobol.
    Hbo19 = 3,
    /// Owen-Sobol shared by the seeds of a block, each seed a fixed offset into every aligned
    /// chunk of 64 points (`sobol::block_net_bits`; `sort-cycle`'s seeds).
    BlockNet = 4,
}

impl Sampler {
    pub const ALL: [Sampler; 5] = [
        Sampler::White,
        Sampler::Sobol,
        Sampler::R2,
        Sampler::Hbo19,
        Sampler::BlockNet,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Sampler::White => "white",
            Sampler::Sobol => "sobol",
            Sampler::R2 => "r2",
            Sampler::Hbo19 => "hbo19",
            Sampler::BlockNet => "blocknet",
        }
    }
}

/// A sampler evaluator holding the Sobol direction numbers (and HBO+19 keys, if any).
#[derive(Debug, Clone)]
pub struct Samples {
    dirs: [[u32; 32]; 4],
    keys: Option<std::sync::Arc<hbo19::KeyTable>>,
}

impl Default for Samples {
    fn default() -> Self {
        Self {
            dirs: sobol::direction_numbers(),
            keys: None,
        }
    }
}

impl Samples {
    /// An evaluator whose `hbo19` sampler uses `keys`.
    pub fn with_keys(keys: hbo19::KeyTable) -> Self {
        Self {
            keys: Some(std::sync::Arc::new(keys)),
            ..Self::default()
        }
    }

    /// The sample as a 32-bit fraction (the GLSL `sample_bits`).
    pub fn bits(&self, sampler: Sampler, seed: u32, index: u32, dim: u32) -> u32 {
        match sampler {
            Sampler::White => rng::hash3(seed, index, dim),
            Sampler::Sobol => sobol::owen_sobol_bits(seed, index, dim, &self.dirs),
            Sampler::R2 => r2::r2_bits(seed, index, dim),
            Sampler::Hbo19 => match &self.keys {
                Some(k) => k.bits(seed, index, dim, &self.dirs),
                None => sobol::owen_sobol_bits(seed, index, dim, &self.dirs),
            },
            Sampler::BlockNet => sobol::block_net_bits(seed, index, dim, &self.dirs),
        }
    }

    /// The sample in [0, 1) (the GLSL `sample_1d`).
    pub fn get(&self, sampler: Sampler, seed: u32, index: u32, dim: u32) -> f32 {
        rng::to_unit(self.bits(sampler, seed, index, dim))
    }
}

/// GLSL constants for `shaders/include/generated/sobol.glsl` (direction numbers and R2 alphas).
pub fn glsl_header() -> String {
    let dirs = sobol::direction_numbers();
    let mut body = String::from(
        "// Sobol direction numbers of dimensions 0..3, MSB-aligned, 32 per dimension.\n",
    );
    let list: Vec<String> = dirs
        .iter()
        .flatten()
        .map(|d| format!("0x{d:08x}u"))
        .collect();
    body += &format!(
        "const uint SOBOL_DIRECTIONS[128] = uint[](\n    {});\n",
        list.join(", ")
    );
    body += &format!(
        "const uint R2_ALPHA_X = {}u;\nconst uint R2_ALPHA_Y = {}u;\n",
        r2::ALPHA[0],
        r2::ALPHA[1]
    );
    body += &format!("const uint SOBOL_GROUP_DIMS = {}u;\n", sobol::GROUP_DIMS);
    for s in Sampler::ALL {
        body += &format!(
            "const uint SAMPLER_{} = {}u;\n",
            s.name().to_uppercase(),
            s as u32
        );
    }
    format!(
        "// GENERATED from Rust by blueshift-sampling. Do not edit: regenerate with\n\
         // `cargo run -p blueshift-headers -- --write`.\n\
         #ifndef GENERATED_SOBOL_GLSL\n#define GENERATED_SOBOL_GLSL\n\n{body}\n#endif\n"
    )
}
