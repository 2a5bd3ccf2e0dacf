//! Frame-0 seed maps (random, or HBO+19 tile positions) and the HBO+19 key buffer contents.
use crate::{MethodAssets, RenderConfig, RenderError, Result};
use blueshift_permute::Screen;
use blueshift_sampling::Sampler;

/// Where the permutation methods start from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SeedMap {
    /// Distinct hashed seeds: frame 0 is white noise.
    #[default]
    Random,
    /// For `sort` / `sort-retarget`: seed = the pixel's position in the HBO+19 key tile, with
    /// the `hbo19` sampler (unless overridden): frame 0 is already blue, the permutation
    /// passes keep it so.
    Hbo19,
}

impl SeedMap {
    pub const ALL: [SeedMap; 2] = [SeedMap::Random, SeedMap::Hbo19];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            SeedMap::Random => "random",
            SeedMap::Hbo19 => "hbo19",
        }
    }
}

impl std::str::FromStr for SeedMap {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                let known: Vec<&str> = Self::ALL.map(SeedMap::name).to_vec();
                format!("unknown seed map '{s}' (known: {})", known.join(", "))
            })
    }
}

/// The initial seed map: distinct for every padded pixel (pcg_hash is a bijection on u32).
pub fn initial_seeds(count: usize, sequence: u32) -> Vec<u32> {
    use blueshift_sampling::rng::pcg_hash;
    let salt = pcg_hash(sequence ^ 0xb5ad_4ece);
    (0..count as u32).map(|i| pcg_hash(i ^ salt)).collect()
}

/// The block-net seed map (`Sampler::BlockNet`) of a padded screen `stride` wide: per
/// [`GRID_BLOCK`]-sized block a hashed block number in the high bits, and in the low six bits
/// the pixel's place in the block XOR a per-block value. Every block holds each of its 64
/// offsets once, so its seeds index one 64-point net.
pub fn block_seeds(count: usize, stride: u32, sequence: u32) -> Vec<u32> {
    use blueshift_sampling::rng::pcg_hash;
    use blueshift_sampling::sobol::BLOCK_NET_LOCAL_BITS;
    const B: u32 = crate::GRID_BLOCK;
    const _: () = assert!(B * B == 1 << BLOCK_NET_LOCAL_BITS);
    let salt = pcg_hash(sequence ^ 0x0b10_c4e7);
    (0..count as u32)
        .map(|i| {
            let (x, y) = (i % stride, i / stride);
            let h = pcg_hash((y / B * stride.div_ceil(B) + x / B) ^ salt);
            let local = ((y % B) * B + x % B) ^ (h >> (32 - BLOCK_NET_LOCAL_BITS));
            (h << BLOCK_NET_LOCAL_BITS) | local
        })
        .collect()
}

/// The HBO+19 seed map of a padded screen `stride` wide: each pixel's position in the key
/// tile, the tile shifted by a per-sequence offset (sequence 0: no shift).
pub fn tile_seeds(count: usize, stride: u32, tile: u32, sequence: u32) -> Vec<u32> {
    use blueshift_sampling::rng::hash3;
    let (ox, oy) = if sequence == 0 {
        (0, 0)
    } else {
        (hash3(sequence, 1, 0x711e), hash3(sequence, 2, 0x711e))
    };
    (0..count as u32)
        .map(|i| {
            let (x, y) = (i % stride, i / stride);
            (y.wrapping_add(oy) % tile) * tile + x.wrapping_add(ox) % tile
        })
        .collect()
}

/// The frame-0 seed map of `cfg` on `screen`.
pub(crate) fn seeds_of(
    cfg: &RenderConfig,
    screen: &Screen,
    assets: &MethodAssets,
) -> Result<Vec<u32>> {
    if cfg.method.anchors_mask() {
        return Ok(blueshift_permute::initial_anchors(
            screen.seed_count(),
            screen.stride(),
        ));
    }
    if cfg.effective_sampler() == Sampler::BlockNet {
        return Ok(block_seeds(
            screen.seed_count(),
            screen.stride(),
            cfg.sequence,
        ));
    }
    if !cfg.tile_seeds() {
        return Ok(initial_seeds(screen.seed_count(), cfg.sequence));
    }
    let keys = assets.keys_for(cfg.spp).ok_or_else(no_keys)?;
    Ok(tile_seeds(
        screen.seed_count(),
        screen.stride(),
        keys.tile,
        cfg.sequence,
    ))
}

fn no_keys() -> RenderError {
    RenderError::Asset(blueshift_assets::AssetError::Missing(
        "no HBO+19 key tables (assets/keys/hbo19_*.bin; `blueshift-tools assets` makes them)"
            .into(),
    ))
}

/// The key buffer contents for `cfg`: the table for its spp, or a one-key placeholder when the
/// sampler is not `hbo19` (the binding must exist in every trace variant).
pub(crate) fn key_words(
    cfg: &RenderConfig,
    assets: &MethodAssets,
) -> Result<(Vec<[u32; 2]>, Option<u32>)> {
    match assets.keys_for(cfg.spp) {
        Some(k) => Ok((k.gpu_words(), Some(k.spp))),
        None if cfg.effective_sampler() == Sampler::Hbo19 => Err(no_keys()),
        None => Ok((vec![[1, 1], [0, 0]], None)),
    }
}
