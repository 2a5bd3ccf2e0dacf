//! Submitting a [`Recorder`]'s commands: with or without waiting (frames in flight), the
//! per-pass times, and failures turned into errors that name the passes.
use crate::commands::{PassTime, Recorder};
use crate::error::{DeviceError, Result, VkContext};
use ash::vk;

impl Recorder {
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
        self.submit_with(wait, signal)?;
        self.wait()
    }

    /// Ends recording and submits without waiting: [`Self::wait`] (or the next
    /// [`Self::begin`]) waits. Host reads of what it wrote are valid after the wait.
    pub fn submit(&mut self) -> Result<()> {
        self.submit_with(&[], &[])
    }

    /// [`Self::submit`] with semaphores, as in [`Self::submit_and_wait_with`].
    pub fn submit_with(
        &mut self,
        wait: &[(vk::Semaphore, vk::PipelineStageFlags)],
        signal: &[vk::Semaphore],
    ) -> Result<()> {
        self.check_recording()?;
        if self.open_pass.is_some() {
            self.end_pass()?;
        }
        self.recording = false;
        let d = self.dev.raw();
        let host = vk::MemoryBarrier::default()
            .src_access_mask(vk::AccessFlags::MEMORY_WRITE)
            .dst_access_mask(vk::AccessFlags::HOST_READ);
        // SAFETY: recording; makes the submission's writes visible to host reads.
        unsafe {
            d.cmd_pipeline_barrier(
                self.cmd,
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::PipelineStageFlags::HOST,
                vk::DependencyFlags::empty(),
                &[host],
                &[],
                &[],
            );
        }
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
        };
        self.pending = run.is_ok();
        run.map_err(|e| self.classify(e))
    }

    /// Whether a submission is pending (submitted, not waited for).
    pub fn is_pending(&self) -> bool {
        self.pending
    }

    /// Waits for the pending submission and returns its per-pass times.
    pub fn wait(&mut self) -> Result<Vec<PassTime>> {
        if !self.pending {
            return Err(DeviceError::Usage(
                "wait without a pending submission".into(),
            ));
        }
        self.pending = false;
        let d = self.dev.raw();
        // SAFETY: the fence belongs to the pending submission.
        let run = unsafe {
            d.wait_for_fences(&[self.fence], true, u64::MAX)
                .vk("vkWaitForFences")
                .and_then(|_| d.reset_fences(&[self.fence]).vk("vkResetFences"))
        };
        let run = match (&self.oom_in_pass, run) {
            (Some(p), Ok(())) if self.passes.contains(p) => Err(DeviceError::Vulkan {
                what: "vkQueueSubmit, simulated by BLUESHIFT_TEST_SUBMIT_OOM".into(),
                result: vk::Result::ERROR_OUT_OF_DEVICE_MEMORY,
            }),
            (_, run) => run,
        };
        match run {
            Ok(()) if self.markers_frozen => {
                Err(self.device_lost("simulated by BLUESHIFT_TEST_DEVICE_LOST"))
            }
            Ok(()) => self.timings(),
            Err(e) => Err(self.classify(e)),
        }
    }

    /// A lost device blamed on a pass, or running out of memory with the submission's passes.
    fn classify(&self, e: DeviceError) -> DeviceError {
        match e {
            DeviceError::Vulkan { what, result } if result == vk::Result::ERROR_DEVICE_LOST => {
                self.device_lost(&what)
            }
            DeviceError::Vulkan { what, result }
                if matches!(
                    result,
                    vk::Result::ERROR_OUT_OF_DEVICE_MEMORY | vk::Result::ERROR_OUT_OF_HOST_MEMORY
                ) =>
            {
                DeviceError::SubmitOutOfMemory {
                    passes: self.passes.join(", "),
                    what,
                    result,
                }
            }
            e => e,
        }
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
