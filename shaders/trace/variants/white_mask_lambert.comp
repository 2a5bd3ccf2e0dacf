#version 460
// Path-tracer variant: sampler white, blue-noise mask on, textures off, Lambert BRDF only.
// See ../trace_body.glsl.
#define TRACE_SAMPLER_KIND SAMPLER_WHITE
#define TRACE_MASK 1
#define TRACE_TEXTURES 0
#define TRACE_LAMBERT 1
#include "../trace_body.glsl"
