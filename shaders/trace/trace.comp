#version 460
// The path tracer with every choice made at run time (sampler, mask, textures); the renderer
// uses the specialised variants of blueshift_layout::variants. See trace_body.glsl.
#define TRACE_SAMPLER_KIND P.sampler_kind
#define TRACE_MASK 1
#define TRACE_TEXTURES 1
#include "trace_body.glsl"
