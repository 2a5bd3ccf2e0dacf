//! The seed-reprojection passes on the GPU (`permute/reproject_*`), with the scratch buffers
//! they need for one screen. See reproject.rs for the algorithm and the CPU twins.
use crate::{Result, Screen};
use blueshift_device::{Binding, Buffer, ComputePipeline, Device, MemoryLocation, Recorder, Res};
use blueshift_layout::motion::{MotionParams, REPROJECT_NONE};

/// Pipelines and scratch buffers of seed reprojection for one screen size.
pub struct Reprojection {
    motion_pass: ComputePipeline,
    claim_pass: ComputePipeline,
    gather_pass: ComputePipeline,
    fill_pass: ComputePipeline,
    scatter_pass: ComputePipeline,
    /// Source pixel per padded pixel (step 1's output; tests may write any field here).
    pub src: Buffer,
    claim: Buffer,
    rows: Buffer,
    holes: Buffer,
    leftovers: Buffer,
    /// Sum x, sum y, count of the winners' motion.
    pub motion: Buffer,
    /// [`Self::motion`] copied at the end of the reprojection, host-readable after it.
    motion_readback: Buffer,
}

impl std::fmt::Debug for Reprojection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Reprojection").finish_non_exhaustive()
    }
}

fn storage(names: &[&'static str]) -> Vec<Binding> {
    names
        .iter()
        .enumerate()
        .map(|(i, n)| Binding::storage(i as u32, n))
        .collect()
}

impl Reprojection {
    pub fn new(dev: &Device, screen: &Screen) -> Result<Self> {
        let push = size_of::<MotionParams>();
        let pipe = |name: &str, b: &[&'static str]| -> Result<ComputePipeline> {
            Ok(blueshift_shaders::pipeline(dev, name, &storage(b), push)?)
        };
        let n = screen.seed_count() as u64;
        let rows = 2 * screen.padded_height() as u64;
        let buf =
            |name: &str, words: u64| Buffer::new(dev, name, words * 4, MemoryLocation::GpuOnly);
        Ok(Self {
            motion_pass: pipe("permute/reproject_motion", &["prev", "cur", "src"])?,
            claim_pass: pipe("permute/reproject_claim", &["src", "claim"])?,
            gather_pass: pipe(
                "permute/reproject_gather",
                &["src", "claim", "seeds_in", "seeds_out", "rows", "motion"],
            )?,
            fill_pass: pipe(
                "permute/reproject_fill",
                &["src", "claim", "rows", "holes", "leftovers"],
            )?,
            scatter_pass: pipe(
                "permute/reproject_scatter",
                &["holes", "leftovers", "seeds_in", "seeds_out"],
            )?,
            src: buf("reproject.src", n)?,
            claim: buf("reproject.claim", n)?,
            rows: buf("reproject.rows", rows)?,
            holes: buf("reproject.holes", n)?,
            leftovers: buf("reproject.leftovers", n)?,
            motion: buf("reproject.motion", 3)?,
            motion_readback: Buffer::new(
                dev,
                "reproject.motion.readback",
                12,
                MemoryLocation::GpuToCpu,
            )?,
        })
    }

    /// Records step 1: `src` from the previous and current G-buffers.
    pub fn reproject_motion(
        &self,
        rec: &mut Recorder,
        p: &MotionParams,
        prev: &Buffer,
        cur: &Buffer,
    ) -> Result<()> {
        let groups = [p.padded_width.div_ceil(8), p.padded_height.div_ceil(8), 1];
        rec.dispatch(
            &self.motion_pass,
            &[
                ("prev", prev.into()),
                ("cur", cur.into()),
                ("src", (&self.src).into()),
            ],
            bytemuck::bytes_of(p),
            groups,
        )?;
        Ok(())
    }

    /// Records steps 2-5: `seeds_out` = `seeds_in` moved along `src` (a permutation again);
    /// the winners' motion sums land in [`Self::motion`].
    pub fn reproject_seeds(
        &self,
        rec: &mut Recorder,
        p: &MotionParams,
        seeds_in: &Buffer,
        seeds_out: &Buffer,
    ) -> Result<()> {
        let push = bytemuck::bytes_of(p);
        let pixels = [(p.padded_width * p.padded_height).div_ceil(64), 1, 1];
        rec.fill_buffer(&self.claim, REPROJECT_NONE)?;
        rec.fill_buffer(&self.holes, REPROJECT_NONE)?;
        rec.fill_buffer(&self.rows, 0)?;
        rec.fill_buffer(&self.motion, 0)?;
        let src = ("src", Res::from(&self.src));
        let claim = ("claim", Res::from(&self.claim));
        let rows = ("rows", Res::from(&self.rows));
        let holes = ("holes", Res::from(&self.holes));
        let leftovers = ("leftovers", Res::from(&self.leftovers));
        let (seeds_in, seeds_out) = (
            ("seeds_in", seeds_in.into()),
            ("seeds_out", seeds_out.into()),
        );
        rec.dispatch(&self.claim_pass, &[src, claim], push, pixels)?;
        rec.dispatch(
            &self.gather_pass,
            &[
                src,
                claim,
                seeds_in,
                seeds_out,
                rows,
                ("motion", (&self.motion).into()),
            ],
            push,
            pixels,
        )?;
        rec.dispatch(
            &self.fill_pass,
            &[src, claim, rows, holes, leftovers],
            push,
            [p.padded_height.div_ceil(64), 1, 1],
        )?;
        rec.dispatch(
            &self.scatter_pass,
            &[holes, leftovers, seeds_in, seeds_out],
            push,
            pixels,
        )?;
        rec.copy_buffer(&self.motion, &self.motion_readback, None)?;
        Ok(())
    }

    /// The winners' motion sums of the last submitted reprojection.
    pub fn read_motion(&self) -> Result<[i32; 3]> {
        let m = self.motion_readback.read::<i32>()?;
        Ok([m[0], m[1], m[2]])
    }
}
