// GENERATED from Rust by blueshift-layout. Do not edit: regenerate with
// `cargo run -p blueshift-headers -- --write`.
#ifndef GENERATED_MOTION_GLSL
#define GENERATED_MOTION_GLSL

struct GBufferTexel {
    vec3 position; // offset 0, size 12
    uint material; // offset 12, size 4
    vec3 normal; // offset 16, size 12
    float depth; // offset 28, size 4
};
const uint G_BUFFER_TEXEL_SIZE = 32;

struct MotionParams {
    vec3 cam_origin; // offset 0, size 12
    vec3 cam_forward; // offset 12, size 12
    vec3 cam_right; // offset 24, size 12
    vec3 cam_up; // offset 36, size 12
    vec2 view_offset; // offset 48, size 8
    vec2 view_size; // offset 56, size 8
    uint width; // offset 64, size 4
    uint height; // offset 68, size 4
    uint padded_width; // offset 72, size 4
    uint padded_height; // offset 76, size 4
};
const uint MOTION_PARAMS_SIZE = 80;

struct HistoryParams {
    uint width; // offset 0, size 4
    uint height; // offset 4, size 4
    uint padded_width; // offset 8, size 4
    uint has_history; // offset 12, size 4
    uint min_frames; // offset 16, size 4
    uint max_frames; // offset 20, size 4
};
const uint HISTORY_PARAMS_SIZE = 24;

struct TaaParams {
    MotionParams camera; // offset 0, size 80
    uint still; // offset 80, size 4
};
const uint TAA_PARAMS_SIZE = 84;

const uint REPROJECT_NONE = 4294967295u;
const uint HISTORY_MIN_FRAMES = 4u;
const uint HISTORY_MAX_FRAMES = 64u;
const uint HISTORY_STRIP = 16u;
const uint HISTORY_COLUMNS = 4u;
const float REPROJECT_TIE_BIAS = 0.00390625;
const int REPROJECT_MAX_MOTION = 255;
const float SIMILAR_MIN_COS = 0.9;
const float SIMILAR_PLANE_DISTANCE = 0.02;
const float TAA_ALPHA = 0.1;
const float TAA_SNAP = 256.0;
#endif
