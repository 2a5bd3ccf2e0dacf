//! CPU twins of `shaders/permute/sort_seeds.glsl`: sorting, and the retargeting that its
//! `SORT_RETARGET` variant applies on the way out. Same inputs, same arithmetic (integer
//! ranks, over keys from the same float operations in the same order), so the GPU must agree
//! exactly.
use crate::skew::count_skewed_classes;
use crate::{PermuteError, Result, SortParams};

/// Sort key of a float (a luminance, or a signed error for history keys): a u32 that orders
/// like the value, so ranking is exact. Positive floats set the top bit over their bit
/// pattern; negative ones invert theirs (larger magnitude, smaller key); 0, -0 and NaN all
/// map to 0x8000_0000, between the two.
#[inline]
pub fn sort_key(v: f32) -> u32 {
    if v > 0.0 {
        0x8000_0000 | v.to_bits()
    } else if v < 0.0 {
        !v.to_bits()
    } else {
        0x8000_0000
    }
}

/// Ranks (class, key, in-block index) triples: element i gets the number of elements before it.
fn ranks(keys: &[(u32, u32, usize)]) -> Vec<usize> {
    keys.iter()
        .map(|a| keys.iter().filter(|b| *b < a).count())
        .collect()
}

/// Sorting pass, in place on the padded seed buffer. `lum` is the raw frame estimate's
/// luminance, `width * height`, row-major; `mask` holds N*N distinct ranks.
///
/// Per block, the seed of the k-th darkest pixel moves to the position of the k-th smallest
/// mask value; partial blocks at the screen edge sort their visible pixels among themselves.
/// `classes` (per visible pixel, e.g. from classify_pixels; all equal for the paper's method):
/// pixels and mask values rank on (class, key, index), so seeds only move within a class.
/// With `p.pairs`, classes should be in-block indices (below 64, as classify_pixels writes):
/// the thin-class test merges classes from 63 up. The GPU pass packs classes into 26 bits of
/// its sort keys, so it agrees for classes below 2^26.
/// `history` (per visible pixel; zeros: the raw key) is subtracted from the key before
/// ranking; NaN stands for the mean key of the pixel's class in the block (history_key_cpu).
/// Returns (skewed classes, classes counted) summed over the blocks with `p.count_skew`
/// (`count_skewed_classes`), else zeros: the GPU pass's stats.
pub fn sort_seeds_cpu(
    p: &SortParams,
    lum: &[f32],
    mask: &[u32],
    classes: &[u32],
    history: &[f32],
    seeds: &mut [u32],
) -> [u32; 2] {
    assert_ne!(
        p.pairs,
        blueshift_layout::params::SORT_PAIRS_FROM_GATE,
        "the twin takes the gate's choice resolved (PairsGate::pairs)"
    );
    let mut stats = [0, 0];
    let n = p.mask_size;
    let (bx, by) = crate::block_counts(p);
    for block in 0..bx * by {
        // Visible pixels of the block in row-major in-block order.
        let px = crate::block_pixels(p, block);
        let at = |x: u32, y: u32| (y * p.width + x) as usize;
        // Sum and count of the keys per class (classes from 63 up merged, as on the GPU).
        let (mut sum, mut count) = ([0f32; 64], [0f32; 64]);
        for &(x, y, _) in &px {
            let c = classes[at(x, y)].min(63) as usize;
            sum[c] += lum[at(x, y)];
            count[c] += 1.0;
        }
        let keys: Vec<f32> = px
            .iter()
            .map(|&(x, y, _)| {
                let (v, h) = (lum[at(x, y)], history[at(x, y)]);
                let c = classes[at(x, y)].min(63) as usize;
                v - if h.is_nan() {
                    sum[c] * (1.0 / count[c])
                } else {
                    h
                }
            })
            .collect();
        let block_classes: Vec<u32> = px.iter().map(|&(x, y, _)| classes[at(x, y)]).collect();
        if p.count_skew != 0 {
            let [skewed, counted] = count_skewed_classes(&block_classes, &keys, &count);
            stats = [stats[0] + skewed, stats[1] + counted];
        }
        let lum_keys: Vec<_> = block_classes
            .iter()
            .zip(&keys)
            .zip(&px)
            .map(|((&c, &k), &(_, _, i))| (c, sort_key(k), i))
            .collect();
        let mask_keys: Vec<_> = px
            .iter()
            .map(|&(x, y, i)| {
                let (mx, my) = ((x + p.offset_x) % n, (y + p.offset_y) % n);
                (
                    classes[(y * p.width + x) as usize],
                    mask[(my * n + mx) as usize],
                    i,
                )
            })
            .collect();
        let mask_keys = if p.pairs != 0 {
            pair_thin_classes(p, &px, mask_keys)
        } else {
            mask_keys
        };
        let lum_rank = ranks(&lum_keys);
        let mask_rank = ranks(&mask_keys);
        let mut pos_of_mask_rank = vec![0usize; px.len()];
        for (j, &r) in mask_rank.iter().enumerate() {
            pos_of_mask_rank[r] = j;
        }
        let old: Vec<u32> = px
            .iter()
            .map(|&(x, y, _)| seeds[(y * p.stride + x) as usize])
            .collect();
        for (j, &r) in lum_rank.iter().enumerate() {
            let (dx, dy, _) = px[pos_of_mask_rank[r]];
            seeds[(dy * p.stride + dx) as usize] = old[j];
        }
    }
    stats
}

/// Twin of `pair_thin_classes` in sort_seeds.glsl: in classes at most 2 pixels wide or tall
/// in the block (every class with `pairs == 2`), one checkerboard colour keeps its mask keys
/// (the lower half of the class's ranks) and the other takes the upper half in the reverse
/// order of its partner's key (partner: same class, left, else right, above, below), so
/// neighbours hold opposite errors.
fn pair_thin_classes(
    p: &SortParams,
    px: &[(u32, u32, usize)],
    keys: Vec<(u32, u32, usize)>,
) -> Vec<(u32, u32, usize)> {
    let b = p.block as usize;
    // Bounding box per class (classes are in-block indices: keyed by min(class, 63) like the
    // shader), and the visible pixel at each in-block index.
    let mut boxes = [(usize::MAX, usize::MAX, 0, 0); 64];
    let mut at = [None; 64];
    for (j, &(class, _, i)) in keys.iter().enumerate() {
        let bx = &mut boxes[class.min(63) as usize];
        *bx = (
            bx.0.min(i % b),
            bx.1.min(i / b),
            bx.2.max(i % b),
            bx.3.max(i / b),
        );
        at[i] = Some(j);
    }
    keys.iter()
        .zip(px)
        .map(|(&(class, key, i), &(x, y, _))| {
            let (x0, y0, x1, y1) = boxes[class.min(63) as usize];
            let thin = p.pairs == 2 || x1 - x0 < 2 || y1 - y0 < 2;
            if !thin || (x + y + p.phase) & 1 == 0 {
                return (class, key, i);
            }
            let (cx, cy) = ((i % b) as i64, (i / b) as i64);
            let partner = [(-1, 0), (1, 0), (0, -1), (0, 1)]
                .iter()
                .map(|&(dx, dy)| (cx + dx, cy + dy))
                .filter(|&(qx, qy)| qx >= 0 && qy >= 0 && qx < b as i64 && qy < b as i64)
                .filter_map(|(qx, qy)| at[qy as usize * b + qx as usize])
                .find(|&j| keys[j].0 == class)
                .map_or(key, |j| keys[j].1);
            (class, 0x1_FFFF - partner, i)
        })
        .collect()
}

/// Retargeting: the seed at padded pixel x moves to x + D((x + o) mod N), toroidally on the
/// padded screen (`stride` x `padded_height`), o the sorting's mask offset. `table` holds D as
/// (dx, dy) per mask texel, row-major. A bijection because the padded screen tiles the mask.
pub fn retarget_seeds_cpu(p: &SortParams, table: &[[i32; 2]], seeds_in: &[u32]) -> Vec<u32> {
    let (w, h, n) = (p.stride as i64, p.padded_height as i64, p.mask_size);
    let mut out = vec![0u32; seeds_in.len()];
    for y in 0..h {
        for x in 0..w {
            let u = ((y as u32 + p.offset_y) % n) * n + (x as u32 + p.offset_x) % n;
            let [dx, dy] = table[u as usize];
            let (tx, ty) = ((x + dx as i64).rem_euclid(w), (y + dy as i64).rem_euclid(h));
            out[(ty * w + tx) as usize] = seeds_in[(y * w + x) as usize];
        }
    }
    out
}

/// The mask the sorting pass reads when it also retargets: per texel the rank in the low 16
/// bits, then D as two signed bytes (dx, dy), so the displacement of a seed's destination
/// comes with the mask value the seed was ranked against, without a load of its own.
pub fn pack_mask_moves(mask: &[u32], table: &[[i32; 2]]) -> Result<Vec<u32>> {
    if mask.len() != table.len() {
        return Err(PermuteError::Invalid(format!(
            "mask of {} texels and retarget table of {} differ in size",
            mask.len(),
            table.len()
        )));
    }
    let byte = |d: i32| u8::try_from(d + 128).map(|b| u32::from(b ^ 0x80));
    mask.iter()
        .zip(table)
        .map(
            |(&rank, &[dx, dy])| match (rank < 0x1_0000, byte(dx), byte(dy)) {
                (true, Ok(x), Ok(y)) => Ok(rank | x << 16 | y << 24),
                _ => Err(PermuteError::Invalid(format!(
                    "mask rank {rank} or displacement ({dx}, {dy}) does not pack into 32 bits \
                 (ranks below 65536, displacements within -128..=127)"
                ))),
            },
        )
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Screen, is_permutation_of, mask_offset};

    fn lcg(s: &mut u64) -> u32 {
        *s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*s >> 33) as u32
    }

    /// A random permutation of 0..n*n as a stand-in mask.
    fn random_mask(n: u32, s: &mut u64) -> Vec<u32> {
        let mut m: Vec<u32> = (0..n * n).collect();
        for i in (1..m.len()).rev() {
            m.swap(i, lcg(s) as usize % (i + 1));
        }
        m
    }

    #[test]
    fn sorting_keeps_a_permutation_for_odd_sizes() {
        let mut s = 1;
        for (w, h) in [(13, 7), (64, 64), (37, 50)] {
            for b in [2, 3, 4, 8] {
                let sc = Screen::new(w, h, 16).unwrap();
                let mask = random_mask(16, &mut s);
                let init: Vec<u32> = (0..sc.seed_count() as u32).collect();
                let mut seeds = init.clone();
                for f in 0..5 {
                    let lum: Vec<f32> = (0..w * h)
                        .map(|_| (lcg(&mut s) % 100) as f32 / 7.0)
                        .collect();
                    let p = sc.sort_params(b, mask_offset(f, (12, 9), 16)).unwrap();
                    let none = vec![0.0; (w * h) as usize];
                    let classes = vec![0; (w * h) as usize];
                    sort_seeds_cpu(&p, &lum, &mask, &classes, &none, &mut seeds);
                    assert!(is_permutation_of(&seeds, &init));
                }
            }
        }
    }

    #[test]
    fn sorting_an_image_equal_to_the_mask_is_the_identity() {
        let mut s = 7;
        let sc = Screen::new(32, 32, 16).unwrap();
        let mask = random_mask(16, &mut s);
        let off = (5, 11);
        let lum: Vec<f32> = (0..32 * 32)
            .map(|i| mask[(((i / 32 + off.1) % 16) * 16 + (i % 32 + off.0) % 16) as usize] as f32)
            .collect();
        let init: Vec<u32> = (0..sc.seed_count() as u32).collect();
        let mut seeds = init.clone();
        sort_seeds_cpu(
            &sc.sort_params(4, off).unwrap(),
            &lum,
            &mask,
            &[0; 32 * 32],
            &[0.0; 32 * 32],
            &mut seeds,
        );
        assert_eq!(seeds, init);
    }

    /// With pairs, a one-pixel-wide class puts the lower half of its keys on one checkerboard
    /// colour (which alternates with the phase) and the upper half on the other; a wide class
    /// keeps the paper's ranking.
    #[test]
    fn thin_classes_rank_against_antithetic_pairs() {
        let mut s = 7;
        let sc = Screen::new(8, 8, 8).unwrap();
        let mask = random_mask(8, &mut s);
        let classes: Vec<u32> = (0..64).map(|i| u32::from(i % 8 == 3)).collect();
        let lum: Vec<f32> = random_mask(8, &mut s)
            .iter()
            .map(|&v| v as f32 + 1.0)
            .collect();
        let init: Vec<u32> = (0..sc.seed_count() as u32).collect();
        for phase in 0..2 {
            let paired = SortParams {
                pairs: 1,
                phase,
                ..sc.sort_params(8, (3, 5)).unwrap()
            };
            let plain = SortParams { pairs: 0, ..paired };
            let (mut a, mut b) = (init.clone(), init.clone());
            let none = [0.0; 64];
            sort_seeds_cpu(&paired, &lum, &mask, &classes, &none, &mut a);
            sort_seeds_cpu(&plain, &lum, &mask, &classes, &none, &mut b);
            // Seeds are their old pixel (stride 8): the key each pixel now holds.
            let column: Vec<f32> = (0..8).map(|y| lum[a[y * 8 + 3] as usize]).collect();
            let mut sorted = column.clone();
            sorted.sort_by(f32::total_cmp);
            for (y, v) in column.iter().enumerate() {
                let low = (3 + y as u32 + phase) % 2 == 0;
                assert_eq!(*v <= sorted[3], low, "phase {phase} row {y}: {column:?}");
            }
            for i in (0..64).filter(|i| i % 8 != 3) {
                assert_eq!(a[i], b[i], "the wide class changed at {i}");
            }
            assert_ne!(a, b, "pairs changed nothing");
            // pairs == 2: the wide class too splits into halves by checkerboard colour.
            let mut c = init.clone();
            sort_seeds_cpu(
                &SortParams { pairs: 2, ..paired },
                &lum,
                &mask,
                &classes,
                &none,
                &mut c,
            );
            let wide: Vec<usize> = (0..64).filter(|i| i % 8 != 3).collect();
            let mut values: Vec<f32> = wide.iter().map(|&i| lum[c[i] as usize]).collect();
            values.sort_by(f32::total_cmp);
            for &i in &wide {
                let low = (i as u32 % 8 + i as u32 / 8 + phase) % 2 == 0;
                let v = lum[c[i] as usize];
                assert_eq!(
                    v <= values[values.len() / 2 - 1],
                    low,
                    "phase {phase} pixel {i}"
                );
            }
        }
    }

    #[test]
    fn retargeting_with_the_identity_table_is_the_identity() {
        let sc = Screen::new(20, 9, 8).unwrap();
        let init: Vec<u32> = (0..sc.seed_count() as u32).collect();
        let out = retarget_seeds_cpu(&sc.sort_params(2, (3, 4)).unwrap(), &[[0, 0]; 64], &init);
        assert_eq!(out, init);
    }

    #[test]
    fn mask_offset_is_exact_integer_shift() {
        assert_eq!(mask_offset(0, (48, 36), 64), (0, 0));
        assert_eq!(mask_offset(1, (48, 36), 64), (48, 36));
        assert_eq!(mask_offset(2, (48, 36), 64), (32, 8));
        assert_eq!(mask_offset(1 << 40, (48, 36), 64), (0, 0));
    }

    /// Sequence 0 keeps the masks in place; sequences 1-8 (what eval reports) each draw
    /// another window of a 64- and of a 128-texel mask, and the shift wraps.
    #[test]
    fn sequences_draw_distinct_mask_windows() {
        use crate::{add_mask_shift, sequence_mask_shift};
        assert_eq!(sequence_mask_shift(0), (0, 0));
        for n in [64u32, 128] {
            let mut seen: Vec<(u32, u32)> = (0..8)
                .map(|s| add_mask_shift((0, 0), sequence_mask_shift(s), n))
                .collect();
            seen.sort_unstable();
            seen.dedup();
            assert_eq!(seen.len(), 8, "side {n}");
        }
        assert_eq!(add_mask_shift((63, 1), (u32::MAX, 66), 64), (62, 3));
    }
}
