#version 460
// Path-tracer variant: sampler r2, blue-noise mask off, textures off, Lambert BRDF only.
// See ../trace_body.glsl.
#define TRACE_SAMPLER_KIND SAMPLER_R2
#define TRACE_MASK 0
#define TRACE_TEXTURES 0
#define TRACE_LAMBERT 1
#include "../trace_body.glsl"
