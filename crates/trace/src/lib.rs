//! The path-tracing pass: the scene on the device ([`SceneBuffers`], [`SceneImages`]), the
//! trace shader's variants and its dispatches split against llvmpipe's loop limit
//! ([`TracePass`]), the loop guard, and the `gbuffer` pass with its CPU twin.
mod buffers;
mod error;
mod gbuffer;
mod images;
mod pass;

pub use blueshift_layout::variants::TraceVariant;
pub use buffers::SceneBuffers;
pub use error::{Result, TraceError};
pub use gbuffer::{GBufferPass, gbuffer_cpu};
pub use images::SceneImages;
pub use pass::{
    LLVMPIPE_LOOP_LIMIT, TRACE_BINDINGS, TRACE_DISPATCH_ITERATIONS, TRACE_FIRST_DISPATCH_VERTICES,
    TRACE_LOOP_GUARD, TRACE_MAX_DISPATCH_VERTICES, TracePass, check_loop_guard,
    next_dispatch_vertices, samples_per_dispatch, trace_variant,
};
