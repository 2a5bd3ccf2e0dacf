//! Command recording: dispatches with push descriptors, copies, per-pass timestamps and crash
//! markers (the index of the pass last started is written to a host-visible buffer, so a lost
//! device can be blamed on a named pass, as kajiya does).
//!
//! Barriers come from what each command declares it reads and writes (a dispatch: its
//! pipeline's bindings, `readonly` ones read, the others written; a copy: source read,
//! destination written): one is recorded only before a command that reads or writes what an
//! earlier command since the last barrier wrote, or writes what one read. Commands on
//! unrelated resources run without one between them.
use crate::device::Device;
use crate::error::{DeviceError, Result, VkContext};
use crate::memory::{Buffer, Image};
use crate::pipeline::{BindingKind, ComputePipeline};
use ash::vk;
use gpu_allocator::MemoryLocation;
use std::collections::HashSet;

/// A resource bound to a binding of a dispatch.
#[derive(Debug, Clone, Copy)]
pub enum Res<'a> {
    Buffer(&'a Buffer),
    Image(&'a Image),
}

impl<'a> From<&'a Buffer> for Res<'a> {
    fn from(b: &'a Buffer) -> Self {
        Res::Buffer(b)
    }
}
impl<'a> From<&'a Image> for Res<'a> {
    fn from(i: &'a Image) -> Self {
        Res::Image(i)
    }
}

/// Time spent in one named pass, from GPU timestamps.
#[derive(Debug, Clone, PartialEq)]
pub struct PassTime {
    pub name: String,
    pub ms: f64,
}

const MAX_PASSES: u32 = 64;

/// One reusable command buffer with its fence, timestamp pool and crash-marker buffer.
pub struct Recorder {
    pub(crate) dev: Device,
    pub(crate) pool: vk::CommandPool,
    pub cmd: vk::CommandBuffer,
    pub(crate) fence: vk::Fence,
    pub(crate) queries: vk::QueryPool,
    pub(crate) markers: Buffer,
    pub(crate) passes: Vec<String>,
    pub(crate) open_pass: Option<usize>,
    pub(crate) recording: bool,
    /// Fault hook ([`crate::faults::DEVICE_LOST`]`=PASS[@N]`): a submission containing pass
    /// PASS (from the N-th such submission on) reports a lost device, as if the GPU hung in
    /// PASS (markers stop after it).
    pub(crate) lose_in_pass: Option<(String, u32)>,
    /// Fault hook ([`crate::faults::SUBMIT_OOM`]`=PASS`): a submission containing pass PASS
    /// reports running out of device memory, through the same error path as the driver's.
    pub(crate) oom_in_pass: Option<String>,
    /// The hook's pass was recorded in this submission; later passes write no marker.
    pub(crate) markers_frozen: bool,
    /// Resources (raw handles) written and read since the last barrier.
    pub(crate) written: HashSet<u64>,
    pub(crate) read: HashSet<u64>,
    /// Barriers recorded in this submission.
    pub(crate) barriers: u32,
    /// Submitted and not yet waited for.
    pub(crate) pending: bool,
}

impl std::fmt::Debug for Recorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Recorder")
            .field("passes", &self.passes)
            .finish()
    }
}

impl Recorder {
    pub fn new(dev: &Device, name: &str) -> Result<Self> {
        let d = dev.raw();
        // SAFETY: valid create infos; destroyed in Drop.
        unsafe {
            let pool = d
                .create_command_pool(
                    &vk::CommandPoolCreateInfo::default()
                        .queue_family_index(dev.queue_family())
                        .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER),
                    None,
                )
                .vk("vkCreateCommandPool")?;
            let cmd = d
                .allocate_command_buffers(
                    &vk::CommandBufferAllocateInfo::default()
                        .command_pool(pool)
                        .level(vk::CommandBufferLevel::PRIMARY)
                        .command_buffer_count(1),
                )
                .vk("vkAllocateCommandBuffers")?[0];
            let fence = d
                .create_fence(&vk::FenceCreateInfo::default(), None)
                .vk("vkCreateFence")?;
            let queries = d
                .create_query_pool(
                    &vk::QueryPoolCreateInfo::default()
                        .query_type(vk::QueryType::TIMESTAMP)
                        .query_count(MAX_PASSES * 2),
                    None,
                )
                .vk("vkCreateQueryPool")?;
            dev.set_name(pool, &format!("{name}.pool"));
            dev.set_name(cmd, &format!("{name}.cmd"));
            dev.set_name(fence, &format!("{name}.fence"));
            dev.set_name(queries, &format!("{name}.timestamps"));
            let markers = Buffer::new(
                dev,
                &format!("{name}.crash_marker"),
                4,
                MemoryLocation::GpuToCpu,
            )?;
            Ok(Self {
                dev: dev.clone(),
                pool,
                cmd,
                fence,
                queries,
                markers,
                passes: Vec::new(),
                open_pass: None,
                recording: false,
                lose_in_pass: crate::faults::device_lost(),
                oom_in_pass: crate::faults::var(crate::faults::SUBMIT_OOM),
                markers_frozen: false,
                written: HashSet::new(),
                read: HashSet::new(),
                barriers: 0,
                pending: false,
            })
        }
    }

    /// Starts recording (resets the command buffer and timestamps), after waiting for this
    /// recorder's previous submission if it is still pending. The first command is a barrier:
    /// everything in this submission comes after everything submitted earlier on the queue.
    pub fn begin(&mut self) -> Result<()> {
        if self.pending {
            self.wait()?;
        }
        let d = self.dev.raw();
        // SAFETY: the previous submission was waited for above.
        unsafe {
            d.reset_command_buffer(self.cmd, vk::CommandBufferResetFlags::empty())
                .vk("vkResetCommandBuffer")?;
            d.begin_command_buffer(
                self.cmd,
                &vk::CommandBufferBeginInfo::default()
                    .flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT),
            )
            .vk("vkBeginCommandBuffer")?;
            d.cmd_reset_query_pool(self.cmd, self.queries, 0, MAX_PASSES * 2);
        }
        self.passes.clear();
        self.open_pass = None;
        self.recording = true;
        self.markers_frozen = false;
        self.barriers = 0;
        self.barrier();
        Ok(())
    }

    pub(crate) fn check_recording(&self) -> Result<()> {
        if self.recording {
            Ok(())
        } else {
            Err(DeviceError::Usage("Recorder used before begin()".into()))
        }
    }

    /// Opens a timed pass: a timestamp and a crash marker. Close it with [`Self::end_pass`].
    pub fn begin_pass(&mut self, name: &str) -> Result<()> {
        self.check_recording()?;
        if self.open_pass.is_some() {
            self.end_pass()?;
        }
        let i = self.passes.len() as u32;
        if i >= MAX_PASSES {
            return Err(DeviceError::Usage(format!(
                "more than {MAX_PASSES} passes in one submission"
            )));
        }
        let lost_here = match &self.lose_in_pass {
            Some((pass, from)) if pass == name => {
                // Counted once per submission, when the pass first appears in it.
                self.markers_frozen
                    || (!self.passes.iter().any(|p| p == name)
                        && crate::faults::count_lost_pass_submission() >= *from)
            }
            _ => false,
        };
        self.passes.push(name.to_string());
        self.open_pass = Some(i as usize);
        let write_marker = !self.markers_frozen;
        self.markers_frozen |= lost_here;
        let d = self.dev.raw();
        // SAFETY: recording; the marker buffer is TRANSFER_DST. The markers are outside the
        // barrier bookkeeping: a diagnostic must not order the passes.
        unsafe {
            if write_marker {
                d.cmd_fill_buffer(self.cmd, self.markers.raw, 0, 4, i + 1);
            }
            d.cmd_write_timestamp(
                self.cmd,
                vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                self.queries,
                2 * i,
            );
        }
        Ok(())
    }

    /// Closes the open pass.
    pub fn end_pass(&mut self) -> Result<()> {
        let Some(i) = self.open_pass.take() else {
            return Err(DeviceError::Usage("end_pass without begin_pass".into()));
        };
        // SAFETY: recording.
        unsafe {
            self.dev.raw().cmd_write_timestamp(
                self.cmd,
                vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                self.queries,
                2 * i as u32 + 1,
            );
        }
        Ok(())
    }

    /// Records a barrier first if a command reading `reads` and writing `writes` depends on a
    /// command recorded since the last one (read or write after write, write after read).
    pub fn access(&mut self, reads: &[u64], writes: &[u64]) {
        let after_write = reads.iter().chain(writes).any(|r| self.written.contains(r));
        if after_write || writes.iter().any(|w| self.read.contains(w)) {
            self.barrier();
        }
        self.read.extend(reads);
        self.written.extend(writes);
    }

    /// Barriers recorded since [`Self::begin`] (the one `begin` records included).
    pub fn barrier_count(&self) -> u32 {
        self.barriers
    }

    /// A full memory barrier between everything before and after (passes are few and large,
    /// so a global barrier costs no more than per-resource ones).
    pub fn barrier(&mut self) {
        self.written.clear();
        self.read.clear();
        self.barriers += 1;
        let mb = vk::MemoryBarrier::default()
            .src_access_mask(vk::AccessFlags::MEMORY_WRITE)
            .dst_access_mask(vk::AccessFlags::MEMORY_READ | vk::AccessFlags::MEMORY_WRITE);
        // SAFETY: recording.
        unsafe {
            self.dev.raw().cmd_pipeline_barrier(
                self.cmd,
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::DependencyFlags::empty(),
                &[mb],
                &[],
                &[],
            );
        }
    }

    /// The device this recorder records for.
    pub fn device(&self) -> &Device {
        &self.dev
    }

    /// Binds `resources` by name (the names the pipeline's shader declares, checked at pipeline
    /// creation; every binding exactly once), pushes constants and dispatches `groups`
    /// workgroups, after a barrier if it depends on an earlier command ([`Self::access`]).
    pub fn dispatch(
        &mut self,
        pipeline: &ComputePipeline,
        resources: &[(&str, Res<'_>)],
        push: &[u8],
        groups: [u32; 3],
    ) -> Result<()> {
        self.check_recording()?;
        let usage = |d: String| DeviceError::Usage(format!("dispatch of '{}': {d}", pipeline.name));
        if let Some((name, _)) = resources
            .iter()
            .find(|(n, _)| !pipeline.bindings.iter().any(|b| b.name == *n))
        {
            return Err(usage(format!("the shader has no resource named '{name}'")));
        }
        let mut ordered = Vec::with_capacity(pipeline.bindings.len());
        for b in &pipeline.bindings {
            let mut given = resources.iter().filter(|(n, _)| *n == b.name);
            match (given.next(), given.next()) {
                (Some((_, r)), None) => ordered.push(*r),
                (None, _) => return Err(usage(format!("nothing bound to '{}'", b.name))),
                (Some(_), Some(_)) => {
                    return Err(usage(format!("'{}' bound more than once", b.name)));
                }
            }
        }
        if push.len() as u32 != pipeline.push_size {
            return Err(usage(format!(
                "{} push bytes, {} declared",
                push.len(),
                pipeline.push_size
            )));
        }
        let max = self.dev.info().max_compute_work_group_count;
        if groups.iter().zip(max).any(|(&g, m)| g > m) {
            return Err(usage(format!(
                "workgroup count {groups:?} over the device limit {max:?}"
            )));
        }
        let mut buffer_infos = Vec::new();
        let mut image_infos = Vec::new();
        for (b, r) in pipeline.bindings.iter().zip(&ordered) {
            match (b.kind, r) {
                (BindingKind::StorageBuffer | BindingKind::UniformBuffer, Res::Buffer(buf)) => {
                    buffer_infos.push(vk::DescriptorBufferInfo {
                        buffer: buf.raw,
                        offset: 0,
                        range: vk::WHOLE_SIZE,
                    });
                }
                (BindingKind::StorageImage, Res::Image(img)) => {
                    image_infos.push(vk::DescriptorImageInfo {
                        sampler: vk::Sampler::null(),
                        image_view: img.view,
                        image_layout: vk::ImageLayout::GENERAL,
                    });
                }
                _ => {
                    return Err(usage(format!(
                        "binding {} ('{}') expects {:?}, got {r:?}",
                        b.binding, b.name, b.kind
                    )));
                }
            }
        }
        let (mut reads, mut writes) = (Vec::new(), Vec::new());
        for (r, &w) in ordered.iter().zip(&pipeline.writes) {
            let handle = match r {
                Res::Buffer(b) => vk::Handle::as_raw(b.raw),
                Res::Image(i) => vk::Handle::as_raw(i.raw),
            };
            if w { &mut writes } else { &mut reads }.push(handle);
        }
        self.access(&reads, &writes);
        let (mut bi, mut ii) = (0, 0);
        let writes: Vec<_> = pipeline
            .bindings
            .iter()
            .map(|b| {
                let w = vk::WriteDescriptorSet::default()
                    .dst_binding(b.binding)
                    .descriptor_type(b.kind.vk());
                if b.kind == BindingKind::StorageImage {
                    ii += 1;
                    w.image_info(&image_infos[ii - 1..ii])
                } else {
                    bi += 1;
                    w.buffer_info(&buffer_infos[bi - 1..bi])
                }
            })
            .collect();
        let d = self.dev.raw();
        // SAFETY: recording; resources outlive the submission (callers wait before dropping).
        unsafe {
            d.cmd_bind_pipeline(self.cmd, vk::PipelineBindPoint::COMPUTE, pipeline.raw);
            self.dev.shared.push_descriptor.cmd_push_descriptor_set(
                self.cmd,
                vk::PipelineBindPoint::COMPUTE,
                pipeline.layout,
                0,
                &writes,
            );
            if !push.is_empty() {
                d.cmd_push_constants(
                    self.cmd,
                    pipeline.layout,
                    vk::ShaderStageFlags::COMPUTE,
                    0,
                    push,
                );
            }
            d.cmd_dispatch(self.cmd, groups[0], groups[1], groups[2]);
        }
        Ok(())
    }
}

impl Drop for Recorder {
    fn drop(&mut self) {
        if self.pending {
            let _ = self.wait();
        }
        // SAFETY: the last submission was waited for above.
        unsafe {
            let d = self.dev.raw();
            d.destroy_query_pool(self.queries, None);
            d.destroy_fence(self.fence, None);
            d.destroy_command_pool(self.pool, None);
        }
    }
}
