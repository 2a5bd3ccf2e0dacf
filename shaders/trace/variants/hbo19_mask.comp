#version 460
// Path-tracer variant: sampler hbo19 (keys from binding 12), blue-noise mask on, textures off.
// See ../trace_body.glsl.
#define TRACE_SAMPLER_KIND SAMPLER_HBO19
#define TRACE_HBO19 1
#define TRACE_MASK 1
#define TRACE_TEXTURES 0
#include "../trace_body.glsl"
