// GENERATED from Rust by blueshift-layout. Do not edit: regenerate with
// `cargo run -p blueshift-headers -- --write`.
#ifndef GENERATED_VIEW_GLSL
#define GENERATED_VIEW_GLSL

struct PresentParams {
    uint out_width; // offset 0, size 4
    uint out_height; // offset 4, size 4
    uint src_width; // offset 8, size 4
    uint src_height; // offset 12, size 4
    uint split_x; // offset 16, size 4
    uint flags; // offset 20, size 4
    float error_scale; // offset 24, size 4
};
const uint PRESENT_PARAMS_SIZE = 28;

const uint PRESENT_FLAG_SPLIT = 1u;
const uint PRESENT_FLAG_ERROR = 2u;
const uint PRESENT_FLAG_BGRA = 4u;
const uint PRESENT_DIVIDER_WIDTH = 2u;
#endif
