//! `sort-grid-adaptive`'s choice of antithetic pairs: in every class while the sorting keys are
//! about symmetric, in none while many classes have heavy-tailed keys. CPU twin of the
//! `pairs_gate` pass (shaders/permute/pairs_gate.comp), which keeps the gate on the GPU so that
//! a frame's sort reads the choice without waiting for the frame before it.
//!
//! Why: pairs pin a pixel's key next to its opposite, which cancels symmetric errors better
//! than a blue-noise mask does (direct light on the box and the edges scene: docs/algorithm.md,
//! "pairs=adaptive"), but cannot cancel a heavy tail (one firefly next to the least negative
//! error), which the mask at least spreads apart: on the box at 8 bounces and 1 spp, pairs in
//! every class lost 0.02-0.03 of P1 against pairs in thin classes, and no pairs at all won
//! 0.005-0.016. The sorting pass counts, per frame, the classes whose keys have a sample
//! skewness |g| > SKEW_LIMIT (`SortParams::count_skew`); the gate smooths that share over
//! frames and decides the next frame's pairs.
use blueshift_layout::params::{PAIRS_GATE_LIMIT, PAIRS_GATE_ONE};

/// Pairs go to every class while the smoothed share of skewed classes is below this (the pass
/// compares in fixed point: `PAIRS_GATE_LIMIT`). Smoothed shares over frames 8-47 on the
/// bundled scenes, all cameras, 1 and 4 spp: the box and the edges scene in direct light at
/// most 0.042, the box at 8 bounces and 1 spp at least 0.127; the textured scene 0.007-0.138
/// and the box at 8 bounces and 4 spp 0.037-0.190 fall either side, where neither choice wins
/// everywhere.
pub const PAIRS_MAX_SKEWED_SHARE: f64 = 0.1;

/// Weight of the newest frame in the smoothed share: about the last 4 frames count, so one
/// unusual frame does not flip the choice.
pub const SKEWED_SHARE_ALPHA: f64 = 0.25;

/// The smoothed share of skewed classes over the frames of one sequence, as the gate's
/// buffer holds it: `[share in units of 1 / PAIRS_GATE_ONE, 1 once a frame counted]`; all
/// zero is a new sequence.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PairsGate {
    words: [u32; 2],
}

impl PairsGate {
    /// The gate its buffer's words describe.
    pub fn from_words(words: [u32; 2]) -> Self {
        Self { words }
    }

    /// The buffer's words.
    pub fn words(&self) -> [u32; 2] {
        self.words
    }

    /// Adds one sorting pass's (skewed classes, classes counted): the newest share weighs
    /// SKEWED_SHARE_ALPHA (1/4), rounded down in fixed point. A frame without counted classes
    /// (nothing on screen, or classes under SKEW_MIN_PIXELS) leaves the share as it is.
    pub fn update(&mut self, [skewed, counted]: [u32; 2]) {
        if counted == 0 {
            return;
        }
        let s = u64::from(skewed.min(counted)) * u64::from(PAIRS_GATE_ONE) / u64::from(counted);
        let share = match self.words[1] {
            0 => s,
            _ => (3 * u64::from(self.words[0]) + s) / 4,
        };
        // Both terms are at most PAIRS_GATE_ONE, so is the mean.
        self.words = [share as u32, 1];
    }

    /// `SortParams::pairs` for the next sorting pass: 2 (every class) unless the keys have
    /// been skewed, then 0 (the mask everywhere, thin classes included).
    pub fn pairs(&self) -> u32 {
        match self.words {
            [share, 1] if share >= PAIRS_GATE_LIMIT => 0,
            _ => 2,
        }
    }

    /// The smoothed share so far (None before the first counted frame).
    pub fn share(&self) -> Option<f64> {
        (self.words[1] != 0).then(|| f64::from(self.words[0]) / f64::from(PAIRS_GATE_ONE))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_everywhere_until_the_keys_are_skewed_and_back_when_they_are_not() {
        let mut g = PairsGate::default();
        assert_eq!(g.pairs(), 2, "no counts yet");
        g.update([0, 0]);
        assert_eq!(g.share(), None, "nothing counted");
        g.update([1, 100]);
        assert_eq!(g.pairs(), 2);
        g.update([40, 100]);
        // 0.01 + 0.25 * 0.39 = 0.1075
        assert_eq!(g.pairs(), 0);
        for _ in 0..20 {
            g.update([2, 100]);
        }
        assert_eq!(g.pairs(), 2);
        assert!((g.share().unwrap() - 0.02).abs() < 1e-3);
    }

    #[test]
    fn one_skewed_frame_among_symmetric_ones_does_not_flip_the_choice() {
        let mut g = PairsGate::default();
        for _ in 0..10 {
            g.update([3, 100]);
        }
        g.update([20, 100]);
        assert_eq!(g.pairs(), 2);
    }

    #[test]
    fn the_limit_is_the_documented_share_and_fixed_point_follows_the_exact_mean() {
        let limit = f64::from(PAIRS_GATE_LIMIT) / f64::from(PAIRS_GATE_ONE);
        assert!(limit >= PAIRS_MAX_SKEWED_SHARE && limit - PAIRS_MAX_SKEWED_SHARE < 1e-6);
        // Against the exponential mean in f64 over a long run of varied counts: rounding down
        // loses under one unit per step, so the gap stays a few units.
        let (mut g, mut exact) = (PairsGate::default(), None::<f64>);
        for i in 0..500u32 {
            let c = [i * 7919 % 97, 97 + i % 13];
            g.update(c);
            let s = f64::from(c[0]) / f64::from(c[1]);
            exact = Some(exact.map_or(s, |e| e + SKEWED_SHARE_ALPHA * (s - e)));
            let gap = (g.share().unwrap() - exact.unwrap()).abs();
            assert!(gap < 4.0 / f64::from(PAIRS_GATE_ONE), "step {i}: {gap}");
        }
        // Counts above the class count (never from the pass) cannot push the share past 1.
        let mut g = PairsGate::default();
        g.update([u32::MAX, 1]);
        assert_eq!(g.share(), Some(1.0));
    }
}
