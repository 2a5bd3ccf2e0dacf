//! Command recording: dispatches with push descriptors, barriers, copies, per-pass timestamps
//! and crash markers (the index of the pass last started is written to a host-visible buffer, so
//! a lost device can be blamed on a named pass, as kajiya does).
use crate::device::Device;
use crate::error::{DeviceError, Result, VkContext};
use crate::memory::{Buffer, Image};
use crate::pipeline::{BindingKind, ComputePipeline};
use ash::vk;
use gpu_allocator::MemoryLocation;

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
    pool: vk::CommandPool,
    pub cmd: vk::CommandBuffer,
    fence: vk::Fence,
    queries: vk::QueryPool,
    markers: Buffer,
    passes: Vec<String>,
    open_pass: Option<usize>,
    recording: bool,
    /// Testing hook (`BLUESHIFT_TEST_DEVICE_LOST=PASS`): a submission containing pass PASS
    /// reports a lost device, as if the GPU hung in PASS (markers stop after it).
    lose_in_pass: Option<String>,
    /// Testing hook (`BLUESHIFT_TEST_SUBMIT_OOM=PASS`): a submission containing pass PASS
    /// reports running out of device memory, through the same error path as the driver's.
    oom_in_pass: Option<String>,
    /// The hook's pass was recorded in this submission; later passes write no marker.
    markers_frozen: bool,
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
                lose_in_pass: std::env::var("BLUESHIFT_TEST_DEVICE_LOST")
                    .ok()
                    .filter(|p| !p.is_empty()),
                oom_in_pass: std::env::var("BLUESHIFT_TEST_SUBMIT_OOM")
                    .ok()
                    .filter(|p| !p.is_empty()),
                markers_frozen: false,
            })
        }
    }

    /// Starts recording (resets the command buffer and timestamps).
    pub fn begin(&mut self) -> Result<()> {
        let d = self.dev.raw();
        // SAFETY: the previous submission was waited for in `submit_and_wait`.
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
        self.passes.push(name.to_string());
        self.open_pass = Some(i as usize);
        let write_marker = !self.markers_frozen;
        self.markers_frozen |= self.lose_in_pass.as_deref() == Some(name);
        let d = self.dev.raw();
        // SAFETY: recording; the marker buffer is TRANSFER_DST.
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
        self.barrier();
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

    /// A full memory barrier between everything before and after (passes are few and large).
    pub fn barrier(&mut self) {
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
    /// workgroups, followed by a barrier.
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
        self.barrier();
        Ok(())
    }

    /// Ends recording, submits, waits, and returns the per-pass times.
    pub fn submit_and_wait(&mut self) -> Result<Vec<PassTime>> {
        self.submit_and_wait_with(&[], &[])
    }

    /// Like [`Self::submit_and_wait`], waiting for the `wait` semaphores (each at its stage)
    /// and signalling `signal` (a swapchain image's acquire and render-finished semaphores).
    pub fn submit_and_wait_with(
        &mut self,
        wait: &[(vk::Semaphore, vk::PipelineStageFlags)],
        signal: &[vk::Semaphore],
    ) -> Result<Vec<PassTime>> {
        self.check_recording()?;
        if self.open_pass.is_some() {
            self.end_pass()?;
        }
        self.recording = false;
        let d = self.dev.raw();
        let cmds = [self.cmd];
        let (wait_sems, wait_stages): (Vec<_>, Vec<_>) = wait.iter().copied().unzip();
        let submit = vk::SubmitInfo::default()
            .command_buffers(&cmds)
            .wait_semaphores(&wait_sems)
            .wait_dst_stage_mask(&wait_stages)
            .signal_semaphores(signal);
        // SAFETY: the command buffer is complete; the fence is unsignalled.
        let run = unsafe {
            d.end_command_buffer(self.cmd)
                .vk("vkEndCommandBuffer")
                .and_then(|_| {
                    d.queue_submit(self.dev.queue(), &[submit], self.fence)
                        .vk("vkQueueSubmit")
                })
                .and_then(|_| {
                    d.wait_for_fences(&[self.fence], true, u64::MAX)
                        .vk("vkWaitForFences")
                })
                .and_then(|_| d.reset_fences(&[self.fence]).vk("vkResetFences"))
        };
        let run = match (&self.oom_in_pass, run) {
            (Some(p), Ok(())) if self.passes.contains(p) => Err(DeviceError::Vulkan {
                what: "vkQueueSubmit, simulated by BLUESHIFT_TEST_SUBMIT_OOM".into(),
                result: vk::Result::ERROR_OUT_OF_DEVICE_MEMORY,
            }),
            (_, run) => run,
        };
        match &run {
            Err(DeviceError::Vulkan { what, result })
                if *result == vk::Result::ERROR_DEVICE_LOST =>
            {
                return Err(self.device_lost(what));
            }
            Err(DeviceError::Vulkan { what, result })
                if matches!(
                    *result,
                    vk::Result::ERROR_OUT_OF_DEVICE_MEMORY | vk::Result::ERROR_OUT_OF_HOST_MEMORY
                ) =>
            {
                return Err(DeviceError::SubmitOutOfMemory {
                    passes: self.passes.join(", "),
                    what: what.clone(),
                    result: *result,
                });
            }
            Ok(()) if self.markers_frozen => {
                return Err(self.device_lost("simulated by BLUESHIFT_TEST_DEVICE_LOST"));
            }
            _ => {}
        }
        run?;
        self.timings()
    }

    fn device_lost(&self, what: &str) -> DeviceError {
        let marker = self
            .markers
            .read::<u32>()
            .ok()
            .and_then(|m| m.first().copied())
            .unwrap_or(0);
        let pass = match marker {
            0 => "(before any pass)".to_string(),
            m => self
                .passes
                .get(m as usize - 1)
                .cloned()
                .unwrap_or_else(|| format!("#{m}")),
        };
        DeviceError::DeviceLost {
            pass,
            what: what.to_string(),
        }
    }

    fn timings(&self) -> Result<Vec<PassTime>> {
        let n = self.passes.len();
        if n == 0 {
            return Ok(Vec::new());
        }
        let mut data = vec![0u64; 2 * n];
        // SAFETY: all queries in range were written by the completed submission.
        unsafe {
            self.dev
                .raw()
                .get_query_pool_results(
                    self.queries,
                    0,
                    &mut data,
                    vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
                )
                .vk("vkGetQueryPoolResults")?;
        }
        let info = self.dev.info();
        let bits = info.timestamp_valid_bits;
        let mask = if bits >= 64 {
            u64::MAX
        } else {
            (1u64 << bits) - 1
        };
        let period = info.timestamp_period_ns as f64;
        Ok(self
            .passes
            .iter()
            .enumerate()
            .map(|(i, name)| {
                let ticks = (data[2 * i + 1] & mask).wrapping_sub(data[2 * i] & mask) & mask;
                PassTime {
                    name: name.clone(),
                    ms: ticks as f64 * period * 1e-6,
                }
            })
            .collect())
    }
}

impl Drop for Recorder {
    fn drop(&mut self) {
        // SAFETY: submissions are always waited for; nothing is pending.
        unsafe {
            let d = self.dev.raw();
            d.destroy_query_pool(self.queries, None);
            d.destroy_fence(self.fence, None);
            d.destroy_command_pool(self.pool, None);
        }
    }
}
