#version 460
// A stand-in for an engine's renderer, for crates/permute/examples/engine.rs: each visible pixel
// draws one number from its seed and the frame (a PCG hash, as any seed-driven sampler would)
// and writes a step-function estimate, the hardest case for a sampler: (value, value, value, key).
#extension GL_EXT_scalar_block_layout : require
layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint width; uint height; uint stride; uint frame; } p;
layout(set = 0, binding = 0, scalar) readonly buffer Seeds { uint seeds[]; };
layout(set = 0, binding = 1, scalar) writeonly buffer Estimate { vec4 estimate[]; };

uint pcg(uint v) {
    uint s = v * 747796405u + 2891336453u;
    uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (w >> 22u) ^ w;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.width * p.height) return;
    uint x = i % p.width, y = i / p.width;
    uint u = pcg(seeds[y * p.stride + x] ^ pcg(p.frame));
    // Half of [0, 1) lit, with a gradient across the screen so neighbours differ in mean.
    float edge = 0.25 + 0.5 * float(x) / float(p.width);
    float v = float(u >> 8u) * (1.0 / 16777216.0) < edge ? 1.0 : 0.0;
    estimate[i] = vec4(v, v, v, v);
}
