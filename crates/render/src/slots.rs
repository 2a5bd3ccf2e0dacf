//! Frames in flight: each frame records into one of [`FRAMES_IN_FLIGHT`] slots (command
//! buffer, fence, timestamps, readback buffers) and is submitted without waiting. A slot is
//! waited for when a frame needs it again, or when the next frame depends on what it read
//! back. Frames on the one queue run in order (each command buffer starts with a barrier), so
//! the serial state (seeds, histories, accumulation) needs no copies.
use crate::{FrameStats, LoopStats, PairsGate, Renderer, Result};
use blueshift_device::{Buffer, Device, MemoryLocation, PassTime, Recorder};
use blueshift_layout::params::TRACE_STATUS_WORDS;

/// Frames recorded and submitted before the oldest is waited for.
pub const FRAMES_IN_FLIGHT: usize = 2;

/// A finished frame: its statistics and, with [`Renderer::set_output_readback`], its images.
#[derive(Debug, Clone)]
pub struct Completed {
    pub stats: FrameStats,
    pub output: Option<FrameOutput>,
}

/// A frame's images as the caller writes them out.
#[derive(Debug, Clone)]
pub struct FrameOutput {
    /// The tonemapped accumulation, RGBA8 per pixel, row-major.
    pub ldr: Vec<u8>,
    /// The frame's raw estimate: (r, g, b, sorting key) per pixel, row-major.
    pub estimate: Vec<[f32; 4]>,
}

/// What a submitted frame still owes once its fence is waited for.
#[derive(Debug)]
struct InFlight {
    frame: u64,
    /// Samples per trace dispatch it ran (the next dispatch size follows its count).
    per_dispatch: u32,
    /// Times of the part of it submitted early and waited for (a mean motion read back).
    times: Vec<PassTime>,
    gate: bool,
    output: bool,
}

/// One frame slot.
pub(crate) struct FrameSlot {
    pub rec: Recorder,
    /// The trace status words, then the two sorting statistics, copied at the frame's end.
    status: Buffer,
    /// ldr and estimate readbacks, when the caller asked for the images.
    output: Option<[Buffer; 2]>,
    in_flight: Option<InFlight>,
}

impl FrameSlot {
    pub fn new(dev: &Device, i: usize) -> Result<Self> {
        let words = TRACE_STATUS_WORDS as u64 + 2;
        let name = format!("frame.slot{i}.status.readback");
        Ok(Self {
            rec: Recorder::new(dev, &format!("frame.slot{i}"))?,
            status: Buffer::new(dev, &name, 4 * words, MemoryLocation::GpuToCpu)?,
            output: None,
            in_flight: None,
        })
    }
}

impl Renderer {
    /// Copies the readback of every following frame's ldr and estimate into its slot, for
    /// [`Completed::output`].
    pub fn set_output_readback(&mut self, on: bool) -> Result<()> {
        self.finish_frames()?;
        let pixels = self.cfg.width as u64 * self.cfg.height as u64;
        for (i, s) in self.slots.iter_mut().enumerate() {
            s.output = match on {
                false => None,
                true => Some([
                    Buffer::new(
                        &self.dev,
                        &format!("frame.slot{i}.ldr.readback"),
                        pixels * 4,
                        MemoryLocation::GpuToCpu,
                    )?,
                    Buffer::new(
                        &self.dev,
                        &format!("frame.slot{i}.estimate.readback"),
                        pixels * 16,
                        MemoryLocation::GpuToCpu,
                    )?,
                ]),
            };
        }
        Ok(())
    }

    /// The frame's last pass: status words (and images) into the slot's readback buffers.
    pub(crate) fn record_readback(&mut self) -> Result<()> {
        let s = &mut self.slots[self.slot];
        s.rec.copy_buffer(&self.res.trace_status, &s.status, None)?;
        if self.recipes.base().adapts_pairs {
            s.rec.copy_region(
                &self.res.pairs_gate,
                &s.status,
                4 * TRACE_STATUS_WORDS as u64,
                8,
            )?;
        }
        if let Some([ldr, estimate]) = &s.output {
            s.rec.copy_buffer(&self.res.ldr, ldr, None)?;
            s.rec.copy_buffer(&self.res.estimate, estimate, None)?;
        }
        Ok(())
    }

    /// Submits the recorded frame and moves on to the next slot.
    pub(crate) fn submit_slot(&mut self, frame: u64, times: Vec<PassTime>) -> Result<()> {
        let output = self.slots[self.slot].output.is_some();
        let s = &mut self.slots[self.slot];
        s.rec.submit()?;
        s.in_flight = Some(InFlight {
            frame,
            per_dispatch: self.per_dispatch,
            times,
            gate: self.recipes.base().adapts_pairs,
            output,
        });
        self.slot = (self.slot + 1) % FRAMES_IN_FLIGHT;
        Ok(())
    }

    /// Waits for slot `i`'s frame, if one is in flight, and takes in what it read back: the
    /// next trace dispatch size, the pairs gate, the loop guard's verdict.
    pub(crate) fn complete_slot(&mut self, i: usize) -> Result<Option<Completed>> {
        let Some(f) = self.slots[i].in_flight.take() else {
            return Ok(None);
        };
        let s = &mut self.slots[i];
        let mut passes = f.times;
        passes.extend(s.rec.wait()?);
        let words = s.status.read::<u32>()?;
        let status = &words[..TRACE_STATUS_WORDS as usize];
        if f.gate {
            let at = TRACE_STATUS_WORDS as usize;
            self.pairs_gate = PairsGate::from_words([words[at], words[at + 1]]);
        }
        let output = match (&s.output, f.output) {
            (Some([ldr, estimate]), true) => {
                let pixels = self.cfg.width as usize * self.cfg.height as usize;
                let ldr = ldr.read::<u32>()?;
                Some(FrameOutput {
                    ldr: bytemuck::cast_slice(&ldr[..pixels]).to_vec(),
                    estimate: estimate.read::<[f32; 4]>()?[..pixels].to_vec(),
                })
            }
            _ => None,
        };
        let stats = FrameStats {
            frame: f.frame,
            passes,
            trace_loop_iterations: status[0],
            loops: self
                .cfg
                .loop_stats
                .then(|| LoopStats::from_status(status))
                .flatten(),
        };
        self.dispatch_vertices = blueshift_trace::next_dispatch_vertices(
            f.per_dispatch,
            self.cfg.bounces,
            stats.trace_loop_iterations,
        );
        blueshift_trace::check_loop_guard(stats.trace_loop_iterations, self.cfg.loop_guard)?;
        Ok(Some(Completed { stats, output }))
    }

    /// Waits for every frame in flight, oldest first.
    pub fn finish_frames(&mut self) -> Result<Vec<Completed>> {
        let mut done = Vec::new();
        for k in 0..FRAMES_IN_FLIGHT {
            let i = (self.slot + k) % FRAMES_IN_FLIGHT;
            done.extend(self.complete_slot(i)?);
        }
        Ok(done)
    }

    /// Whether the next frame must wait for the one before it: its trace splits its samples
    /// by that frame's loop count (only when the spp could need more than one dispatch; the
    /// split changes the rounding of the running mean). The adaptive pairs' gate stays on the
    /// GPU (`pairs_gate` pass), so it never makes a frame wait.
    pub(crate) fn needs_previous(&self) -> bool {
        let fewest = blueshift_trace::samples_per_dispatch(
            blueshift_trace::TRACE_FIRST_DISPATCH_VERTICES,
            self.cfg.bounces,
        );
        self.cfg.spp > fewest
    }
}
