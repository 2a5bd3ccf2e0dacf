// GENERATED from Rust by blueshift-layout. Do not edit: regenerate with
// `cargo run -p blueshift-headers -- --write`.
#ifndef GENERATED_PARAMS_GLSL
#define GENERATED_PARAMS_GLSL

struct SortParams {
    uint width; // offset 0, size 4
    uint height; // offset 4, size 4
    uint stride; // offset 8, size 4
    uint padded_height; // offset 12, size 4
    uint block; // offset 16, size 4
    uint mask_size; // offset 20, size 4
    uint offset_x; // offset 24, size 4
    uint offset_y; // offset 28, size 4
    uint grid_x; // offset 32, size 4
    uint grid_y; // offset 36, size 4
    uint pairs; // offset 40, size 4
    uint phase; // offset 44, size 4
    uint count_skew; // offset 48, size 4
    uint mask_layer; // offset 52, size 4
    uint cycle_phase; // offset 56, size 4
    uint cycle_next_phase; // offset 60, size 4
    uint cycle_next_valid; // offset 64, size 4
    uint cycle_mean_count; // offset 68, size 4
    uint cycle_sample_keys; // offset 72, size 4
};
const uint SORT_PARAMS_SIZE = 76;

struct TraceParams {
    vec3 cam_origin; // offset 0, size 12
    vec3 cam_forward; // offset 12, size 12
    vec3 cam_right; // offset 24, size 12
    vec3 cam_up; // offset 36, size 12
    uint width; // offset 48, size 4
    uint height; // offset 52, size 4
    uint stride; // offset 56, size 4
    uint frame; // offset 60, size 4
    uint spp; // offset 64, size 4
    uint sample_index; // offset 68, size 4
    uint sample_count; // offset 72, size 4
    uint max_bounces; // offset 76, size 4
    uint sampler_kind; // offset 80, size 4
    uint flags; // offset 84, size 4
    uint mask_mode; // offset 88, size 4
    uint mask_size; // offset 92, size 4
    uint mask_step; // offset 96, size 4
    uint mask_offset_x; // offset 100, size 4
    uint mask_offset_y; // offset 104, size 4
    vec2 view_offset; // offset 108, size 8
    vec2 view_size; // offset 116, size 8
};
const uint TRACE_PARAMS_SIZE = 124;

struct ImageParams {
    uint width; // offset 0, size 4
    uint height; // offset 4, size 4
    uint count; // offset 8, size 4
    float exposure; // offset 12, size 4
};
const uint IMAGE_PARAMS_SIZE = 16;

const uint TRACE_FLAG_SALT_FRAME = 1u;
const uint TRACE_FLAG_ADVANCE_INDEX = 2u;
const uint TRACE_FLAG_NO_JITTER = 4u;
const uint TRACE_FLAG_DEMODULATE = 8u;
const uint TRACE_FLAG_MASK_ANCHORED = 16u;
const uint TRACE_FLAG_SOBOL_JITTER = 128u;
const uint TRACE_FLAG_RECORD_PRIMARY = 32u;
const uint TRACE_FLAG_SEED_JITTER_ON_TEXTURES = 64u;
const uint PRIMARY_TEXTURED = 1u;
const uint MASK_DIM_OFFSET_X = 37u;
const uint MASK_DIM_OFFSET_Y = 71u;
const uint TRACE_FLAG_MASK_DIMS_SHIFT = 16u;
const uint ANCHOR_FRAC_BITS = 8u;
const float DEMODULATE_MIN_ALBEDO = 0.02;
const uint MASK_MODE_NONE = 0u;
const uint MASK_MODE_2D = 1u;
const uint MASK_MODE_SPATIOTEMPORAL = 2u;
const uint MASK_MODE_ROTATE = 3u;
const uint MASK_DIMS = 9u;
const uint DIMS_PER_BOUNCE = 7u;
const uint TRACE_GROUP_X = 8u;
const uint TRACE_GROUP_Y = 8u;
const float REC709_LUMA_R = 0.2126;
const float REC709_LUMA_G = 0.7152;
const float REC709_LUMA_B = 0.0722;
const uint SKEW_MIN_PIXELS = 8u;
const uint SAMPLE_KEY_DIM = 2u;
const uint SAMPLE_KEY_BITS = 3u;
const float SKEW_LIMIT = 2.0;
const uint SORT_PAIRS_FROM_GATE = 3u;
const uint PAIRS_GATE_ONE = 16777216u;
const uint PAIRS_GATE_LIMIT = 1677722u;
const uint TRACE_LOOP_PATH_VERTEX = 0u;
const uint TRACE_LOOP_LIGHT_CHOICE = 1u;
const uint TRACE_LOOP_CLOSEST_HIT = 2u;
const uint TRACE_LOOP_CLOSEST_DESCEND = 3u;
const uint TRACE_LOOP_CLOSEST_LEAF = 4u;
const uint TRACE_LOOP_CLOSEST_POP = 5u;
const uint TRACE_LOOP_OCCLUSION = 6u;
const uint TRACE_LOOP_OCCLUSION_WALK = 7u;
const uint TRACE_LOOP_OCCLUSION_LEAF = 8u;
const uint TRACE_LOOP_COUNT = 9u;
const uint TRACE_STATUS_LOOPS = 4u;
#endif
