#version 460
// trace/trace_loop_stats.comp with the hbo19 sampler's key table (binding 12), so that its
// paths are those of the trace/variants/hbo19* pipelines.
#define TRACE_SAMPLER_KIND SAMPLER_HBO19
#define TRACE_HBO19 1
#define TRACE_MASK 1
#define TRACE_TEXTURES 1
#define TRACE_LOOP_STATS 1
#include "trace_body.glsl"
