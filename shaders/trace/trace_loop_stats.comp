#version 460
// The run-time path tracer (trace/trace.comp) counting its loops' iterations per SIMD batch
// and per lane into trace_status (TRACE_LOOP_STATS, trace_body.glsl): `blueshift bench
// --loop-stats`. Its paths, and so its counts, are those of every other variant.
#define TRACE_SAMPLER_KIND P.sampler_kind
#define TRACE_MASK 1
#define TRACE_TEXTURES 1
#define TRACE_LOOP_STATS 1
#include "trace_body.glsl"
