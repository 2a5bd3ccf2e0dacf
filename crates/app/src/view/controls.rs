//! The viewer's settings, how commands change them, and the title-bar readout (all pure).
use super::input::Action;
use blueshift_render::{FrameStats, Method};

/// The methods of keys 1-6: the presets, in their order.
pub const VIEW_METHODS: [Method; Method::PRESETS.len()] = {
    let mut m = [Method::White; Method::PRESETS.len()];
    let mut i = 0;
    while i < m.len() {
        m[i] = Method::PRESETS[i].1;
        i += 1;
    }
    m
};
/// Limits of the interactive controls (the renderer accepts more; these stay interactive).
pub const MAX_SPP: u32 = 64;
pub const MAX_BOUNCES: u32 = 16;
pub const BLOCKS: std::ops::RangeInclusive<u32> = 2..=8;
/// Error view: |estimate - reference| is multiplied by this before display.
pub const ERROR_SCALE: f32 = 4.0;
/// Samples per pixel per frame of the error view's reference (Sobol, accumulating).
pub const REFERENCE_SPP: u32 = 4;

/// What the user controls.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Method of the left (or only) view and of the right view in split-screen.
    pub methods: [Method; 2],
    /// Which side keys 1-6 set (0 = left/only, 1 = right).
    pub side: usize,
    pub spp: u32,
    pub bounces: u32,
    /// The block size keys B / Shift+B set, for the methods that take one.
    pub block: u32,
    pub accumulate: bool,
    pub split: bool,
    pub error: bool,
}

/// What a command changed, for the GPU side to act on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Change {
    Nothing,
    /// The method of a side changed (that renderer restarts; in split-screen both do).
    Method,
    /// spp, bounces or block size changed (accumulation restarts, seeds are kept).
    Quality,
    /// Restart every sequence.
    Reset,
    /// Split-screen was switched on or off.
    Split,
    /// The error view was switched on or off.
    Error,
    /// Accumulation was switched (takes effect with the next frame).
    Accumulation,
    /// Tab: only the readout changes.
    Side,
    Quit,
}

fn step(v: u32, by: i32, lo: u32, hi: u32) -> u32 {
    v.saturating_add_signed(by).clamp(lo, hi)
}

impl Settings {
    /// The block size to give a renderer of `method`: the keys' choice where the method takes
    /// one, its own otherwise.
    pub fn block_for(&self, method: Method) -> Option<u32> {
        method.fixed_block().is_none().then_some(self.block)
    }

    /// Applies a command, keeping every value in range.
    pub fn apply(&mut self, action: Action) -> Change {
        let before = self.clone();
        match action {
            Action::Method(i) => {
                let Some(&m) = VIEW_METHODS.get(i) else {
                    return Change::Nothing;
                };
                let side = if self.split { self.side } else { 0 };
                self.methods[side] = m;
            }
            Action::Spp(d) => {
                // Doubling / halving: 1, 2, 4, ... MAX_SPP.
                self.spp = if d > 0 {
                    self.spp.saturating_mul(2).min(MAX_SPP)
                } else {
                    (self.spp / 2).max(1)
                };
            }
            Action::Bounces(d) => self.bounces = step(self.bounces, d, 1, MAX_BOUNCES),
            Action::Block(d) => self.block = step(self.block, d, *BLOCKS.start(), *BLOCKS.end()),
            Action::ToggleAccumulation => {
                self.accumulate = !self.accumulate;
                return Change::Accumulation;
            }
            Action::Reset => return Change::Reset,
            Action::ToggleSplit => {
                self.split = !self.split;
                return Change::Split;
            }
            Action::ToggleError => {
                self.error = !self.error;
                return Change::Error;
            }
            Action::SwitchSide => {
                self.side = 1 - self.side.min(1);
                return Change::Side;
            }
            Action::Quit => return Change::Quit,
        }
        match action {
            _ if *self == before => Change::Nothing,
            Action::Method(_) => Change::Method,
            _ => Change::Quality,
        }
    }

    /// The methods as the title shows them; in split-screen the side keys 1-7 set is marked.
    pub fn method_label(&self) -> String {
        if !self.split {
            return self.methods[0].name().to_string();
        }
        let mark = |i: usize| {
            let n = self.methods[i].name();
            if self.side == i {
                format!("[{n}]")
            } else {
                n.to_string()
            }
        };
        format!("{} | {}", mark(0), mark(1))
    }
}

/// GPU milliseconds of each pass, summed over the frame's renderers, in pipeline order.
pub fn pass_times(stats: &[FrameStats], present_ms: f64) -> String {
    let mut parts = Vec::new();
    for (name, label) in [
        ("gbuffer", "gbuffer"),
        ("reproject_motion", "motion"),
        ("reproject_seeds", "reproject"),
        ("trace", "trace"),
        ("history_key", "history"),
        ("classify_pixels", "classify"),
        ("sort_seeds", "sort"),
        ("accumulate", "accum"),
        ("taa", "taa"),
        ("tonemap", "tonemap"),
    ] {
        if stats
            .iter()
            .any(|s| s.passes.iter().any(|p| p.name == name))
        {
            let ms: f64 = stats.iter().map(|s| s.ms(name)).sum();
            parts.push(format!("{label} {ms:.1}"));
        }
    }
    parts.push(format!("present {present_ms:.1}"));
    parts.join(" ")
}

/// The title-bar readout of one frame.
pub fn title(s: &Settings, frame_ms: f64, stats: &[FrameStats], present_ms: f64) -> String {
    let mut t = format!(
        "blueshift: {} | {} spp | {} bounces | block {} | {:.1} ms ({:.1} fps) | GPU ms: {}",
        s.method_label(),
        s.spp,
        s.bounces,
        s.methods[0].block(Some(s.block)), // the block the (left) method sorts with
        frame_ms,
        if frame_ms > 0.0 {
            1000.0 / frame_ms
        } else {
            0.0
        },
        pass_times(stats, present_ms),
    );
    if !s.accumulate {
        t += " | no accumulation";
    }
    if s.error {
        t += &format!(" | error x{ERROR_SCALE} vs sobol reference");
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use blueshift_device::PassTime;

    fn settings() -> Settings {
        Settings {
            methods: [Method::SORT_CYCLE, Method::White],
            side: 0,
            spp: 1,
            bounces: 4,
            block: 4,
            accumulate: true,
            split: false,
            error: false,
        }
    }

    #[test]
    fn commands_stay_in_range() {
        let mut s = settings();
        assert_eq!(s.apply(Action::Spp(-1)), Change::Nothing);
        for _ in 0..10 {
            s.apply(Action::Spp(1));
        }
        assert_eq!(s.spp, MAX_SPP);
        for _ in 0..10 {
            s.apply(Action::Block(1));
        }
        assert_eq!(s.block, 8);
        assert_eq!(s.apply(Action::Block(1)), Change::Nothing);
        for _ in 0..20 {
            s.apply(Action::Block(-1));
            s.apply(Action::Bounces(-1));
        }
        assert_eq!((s.block, s.bounces), (2, 1));
        assert_eq!(s.apply(Action::Bounces(1)), Change::Quality);
        assert_eq!(s.apply(Action::Method(VIEW_METHODS.len())), Change::Nothing);
    }

    #[test]
    fn number_keys_set_the_chosen_side() {
        let mut s = settings();
        assert_eq!(s.apply(Action::Method(1)), Change::Method);
        assert_eq!(s.methods, [Method::Sobol, Method::White]);
        assert_eq!(s.apply(Action::SwitchSide), Change::Side);
        s.apply(Action::Method(2));
        assert_eq!(s.methods[0], Method::MaskR2, "side ignored without split");
        assert_eq!(s.apply(Action::ToggleSplit), Change::Split);
        s.apply(Action::Method(3));
        assert_eq!(s.methods, [Method::MaskR2, Method::SORT_RETARGET]);
        assert_eq!(s.method_label(), "mask-r2 | [sort-retarget]");
        assert_eq!(s.apply(Action::Method(3)), Change::Nothing);
        // Every preset has its key, in the presets' order.
        for (i, (_, m)) in Method::PRESETS.iter().enumerate() {
            s.apply(Action::Method(i));
            assert_eq!(s.methods[1], *m);
        }
    }

    #[test]
    fn title_shows_settings_and_pass_times() {
        let stats = FrameStats {
            frame: 3,
            passes: [
                "trace",
                "classify_pixels",
                "sort_seeds",
                "accumulate",
                "tonemap",
            ]
            .iter()
            .map(|n| PassTime {
                name: n.to_string(),
                ms: 2.0,
            })
            .collect(),
            trace_loop_iterations: 0,
            loops: None,
        };
        let mut s = settings();
        s.apply(Action::ToggleAccumulation);
        let t = title(&s, 50.0, &[stats.clone(), stats], 0.3);
        assert!(
            t.contains("sort-cycle | 1 spp | 4 bounces | block 8"),
            "{t}"
        );
        assert!(t.contains("50.0 ms (20.0 fps)"), "{t}");
        assert!(
            t.contains("trace 4.0 classify 4.0 sort 4.0 accum 4.0 tonemap 4.0 present 0.3"),
            "{t}"
        );
        assert!(t.contains("no accumulation"), "{t}");
    }
}
