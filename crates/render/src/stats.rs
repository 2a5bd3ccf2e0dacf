//! What a frame reports: GPU time per pass, the trace pass's loop-limit count and, with
//! [`crate::RenderConfig::loop_stats`], its loop statistics. llvmpipe runs a loop for a whole
//! SIMD batch while any of its lanes is still in it, so the iterations the batches ran, against
//! the lane iterations in them, measure what divergence costs per loop.
use blueshift_device::PassTime;
use blueshift_layout::params::{TRACE_STATUS_LOOPS, TRACE_STATUS_WORDS, TraceLoop};

/// Per-pass GPU times of one frame.
#[derive(Debug, Clone, Default)]
pub struct FrameStats {
    pub frame: u64,
    pub passes: Vec<PassTime>,
    /// The most loop iterations one SIMD batch of the trace pass ran (llvmpipe's limit:
    /// [`crate::LLVMPIPE_LOOP_LIMIT`]).
    pub trace_loop_iterations: u32,
    /// Per-loop iteration counts of the trace pass, with [`crate::RenderConfig::loop_stats`].
    pub loops: Option<LoopStats>,
}

impl FrameStats {
    /// Milliseconds of the pass named `name` (0 if it did not run).
    pub fn ms(&self, name: &str) -> f64 {
        self.passes
            .iter()
            .filter(|p| p.name == name)
            .map(|p| p.ms)
            .sum()
    }
}

/// Iterations of one loop, summed over a frame.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LoopCount {
    /// Over invocations (lanes): the work the rays asked for.
    pub lanes: u64,
    /// Over SIMD batches: iterations in which any lane of the batch was in the loop (what
    /// llvmpipe spends time on).
    pub batches: u64,
}

impl LoopCount {
    /// Share of the lanes busy in the batches' iterations, for batches of `width` lanes (the
    /// device's subgroup size); `None` if the loop never ran.
    pub fn utilization(&self, width: u32) -> Option<f64> {
        (self.batches > 0).then(|| self.lanes as f64 / (self.batches as f64 * width as f64))
    }
}

/// Per-loop counts of one or more frames.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LoopStats {
    counts: [LoopCount; TraceLoop::ALL.len()],
}

impl LoopStats {
    /// From the trace pass's status words (layout: [`TRACE_STATUS_LOOPS`]).
    pub fn from_status(words: &[u32]) -> Option<Self> {
        let loops = words.get(TRACE_STATUS_LOOPS as usize..TRACE_STATUS_WORDS as usize)?;
        let wide = |lo: u32, hi: u32| (hi as u64) << 32 | lo as u64;
        let mut s = Self::default();
        for (c, w) in s.counts.iter_mut().zip(loops.chunks_exact(4)) {
            *c = LoopCount {
                lanes: wide(w[0], w[1]),
                batches: wide(w[2], w[3]),
            };
        }
        Some(s)
    }

    pub fn get(&self, l: TraceLoop) -> LoopCount {
        self.counts[l as usize]
    }

    /// All loops together.
    pub fn total(&self) -> LoopCount {
        self.counts
            .iter()
            .fold(LoopCount::default(), |a, c| LoopCount {
                lanes: a.lanes + c.lanes,
                batches: a.batches + c.batches,
            })
    }

    /// Adds another frame's counts.
    pub fn add(&mut self, other: &LoopStats) {
        for (a, b) in self.counts.iter_mut().zip(&other.counts) {
            a.lanes += b.lanes;
            a.batches += b.batches;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn status_words_are_low_then_high() {
        let mut words = vec![7u32; TRACE_STATUS_WORDS as usize];
        let at = (TRACE_STATUS_LOOPS + 4 * TraceLoop::ClosestLeaf as u32) as usize;
        words[at..at + 4].copy_from_slice(&[5, 1, 0xffff_ffff, 0]);
        let s = LoopStats::from_status(&words).unwrap();
        let leaf = s.get(TraceLoop::ClosestLeaf);
        assert_eq!(leaf.lanes, (1 << 32) + 5);
        assert_eq!(leaf.batches, 0xffff_ffff);
        assert_eq!(s.get(TraceLoop::PathVertex).lanes, (7 << 32) + 7);
        assert!(LoopStats::from_status(&words[..words.len() - 1]).is_none());
    }

    #[test]
    fn utilization_and_totals() {
        let c = LoopCount {
            lanes: 12,
            batches: 3,
        };
        assert_eq!(c.utilization(8), Some(0.5));
        assert_eq!(LoopCount::default().utilization(8), None);
        let words = vec![1u32; TRACE_STATUS_WORDS as usize];
        let mut s = LoopStats::from_status(&words).unwrap();
        s.add(&s.clone());
        let n = TraceLoop::ALL.len() as u64;
        assert_eq!(s.total().batches, 2 * n * ((1 << 32) + 1));
    }
}
