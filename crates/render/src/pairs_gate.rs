//! `sort-grid-adaptive`'s choice of antithetic pairs: in every class while the sorting keys are
//! about symmetric, in none while many classes have heavy-tailed keys.
//!
//! Why: pairs pin a pixel's key next to its opposite, which cancels symmetric errors better
//! than a blue-noise mask does (direct light on the box and the edges scene: docs/algorithm.md "pairs=adaptive"
//! where the errors are symmetric"), but cannot cancel a heavy tail (one firefly next to the least negative error), which the
//! mask at least spreads apart: on the box at 8 bounces and 1 spp, pairs in every class lost
//! 0.02-0.03 of P1 against pairs in thin classes, and no pairs at all won 0.005-0.016. The
//! sorting pass counts, per frame, the classes whose keys have a sample skewness
//! |g| > SKEW_LIMIT (`SortParams::count_skew`); the gate smooths that share over frames and
//! decides the next frame's `SortParams::pairs`.

/// Pairs go to every class while the smoothed share of skewed classes is below this.
/// Smoothed shares over frames 8-47 on the bundled scenes, all cameras, 1 and 4 spp: the box
/// and the edges scene in direct light at most 0.042, the box at 8 bounces and 1 spp at least
/// 0.127; the textured scene 0.007-0.138 and the box at 8 bounces and 4 spp 0.037-0.190 fall
/// either side, where neither choice wins everywhere.
pub const PAIRS_MAX_SKEWED_SHARE: f64 = 0.1;

/// Weight of the newest frame in the smoothed share: about the last 4 frames count, so one
/// unusual frame does not flip the choice.
pub const SKEWED_SHARE_ALPHA: f64 = 0.25;

/// The smoothed share of skewed classes over the frames of one sequence.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairsGate {
    /// None until the first frame's counts arrive.
    share: Option<f64>,
}

impl PairsGate {
    /// Adds one sorting pass's (skewed classes, classes counted). A frame without counted
    /// classes (nothing on screen, or classes under SKEW_MIN_PIXELS) leaves the share as it is.
    pub fn update(&mut self, [skewed, counted]: [u32; 2]) {
        if counted == 0 {
            return;
        }
        let s = f64::from(skewed) / f64::from(counted);
        self.share = Some(match self.share {
            None => s,
            Some(old) => old + SKEWED_SHARE_ALPHA * (s - old),
        });
    }

    /// `SortParams::pairs` for the next sorting pass: 2 (every class) unless the keys have
    /// been skewed, then 0 (the mask everywhere, thin classes included).
    pub fn pairs(&self) -> u32 {
        match self.share {
            Some(s) if s >= PAIRS_MAX_SKEWED_SHARE => 0,
            _ => 2,
        }
    }

    /// `SortParams::pairs` of a sort whose rule is `rule`: 0 none, 1 thin classes, 2 every
    /// class; adaptive pairs take what the gate chose from the sequence's counts so far.
    pub(crate) fn pairs_of(&self, rule: crate::Pairs) -> u32 {
        match rule {
            crate::Pairs::Off => 0,
            crate::Pairs::Thin => 1,
            crate::Pairs::Adaptive => self.pairs(),
            crate::Pairs::All => 2,
        }
    }

    /// The smoothed share so far (None before the first counted frame).
    pub fn share(&self) -> Option<f64> {
        self.share
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
}
