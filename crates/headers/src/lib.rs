//! Every generated GLSL header, from its Rust source of truth. This crate deliberately does not
//! depend on the shader build, so headers can be regenerated even when shaders fail to compile
//! against stale ones: `cargo run -p blueshift-headers -- --write`.
use std::path::{Path, PathBuf};

/// (file stem, header text) for every file in `shaders/include/generated/`.
pub fn all() -> Vec<(&'static str, String)> {
    use blueshift_layout::{Header, motion, params};
    vec![
        ("sobol", blueshift_sampling::glsl_header()),
        ("scene", blueshift_scene::glsl_header()),
        (
            "params",
            Header::new()
                .push::<params::SortParams>()
                .push::<params::TraceParams>()
                .push::<params::ImageParams>()
                .constant("TRACE_FLAG_SALT_FRAME", params::TRACE_FLAG_SALT_FRAME)
                .constant("TRACE_FLAG_ADVANCE_INDEX", params::TRACE_FLAG_ADVANCE_INDEX)
                .constant("TRACE_FLAG_NO_JITTER", params::TRACE_FLAG_NO_JITTER)
                .constant("TRACE_FLAG_DEMODULATE", params::TRACE_FLAG_DEMODULATE)
                .constant("TRACE_FLAG_MASK_ANCHORED", params::TRACE_FLAG_MASK_ANCHORED)
                .constant("TRACE_FLAG_SOBOL_JITTER", params::TRACE_FLAG_SOBOL_JITTER)
                .constant(
                    "TRACE_FLAG_RECORD_PRIMARY",
                    params::TRACE_FLAG_RECORD_PRIMARY,
                )
                .constant(
                    "TRACE_FLAG_SEED_JITTER_ON_TEXTURES",
                    params::TRACE_FLAG_SEED_JITTER_ON_TEXTURES,
                )
                .constant("PRIMARY_TEXTURED", params::PRIMARY_TEXTURED)
                .constant("MASK_DIM_OFFSET_X", params::MASK_DIM_OFFSET_X)
                .constant("MASK_DIM_OFFSET_Y", params::MASK_DIM_OFFSET_Y)
                .constant(
                    "TRACE_FLAG_MASK_DIMS_SHIFT",
                    params::TRACE_FLAG_MASK_DIMS_SHIFT,
                )
                .constant("ANCHOR_FRAC_BITS", params::ANCHOR_FRAC_BITS)
                .constant_f32("DEMODULATE_MIN_ALBEDO", params::DEMODULATE_MIN_ALBEDO)
                .constant("MASK_MODE_NONE", params::MASK_MODE_NONE)
                .constant("MASK_MODE_2D", params::MASK_MODE_2D)
                .constant("MASK_MODE_SPATIOTEMPORAL", params::MASK_MODE_SPATIOTEMPORAL)
                .constant("MASK_MODE_ROTATE", params::MASK_MODE_ROTATE)
                .constant("MASK_DIMS", params::MASK_DIMS)
                .constant("DIMS_PER_BOUNCE", params::DIMS_PER_BOUNCE)
                .constant("TRACE_GROUP_X", params::TRACE_GROUP_X)
                .constant("TRACE_GROUP_Y", params::TRACE_GROUP_Y)
                .constant_f32("REC709_LUMA_R", blueshift_layout::REC709_LUMA[0])
                .constant_f32("REC709_LUMA_G", blueshift_layout::REC709_LUMA[1])
                .constant_f32("REC709_LUMA_B", blueshift_layout::REC709_LUMA[2])
                .constant("SKEW_MIN_PIXELS", params::SKEW_MIN_PIXELS)
                .constant("SAMPLE_KEY_DIM", params::SAMPLE_KEY_DIM)
                .constant("SAMPLE_KEY_BITS", params::SAMPLE_KEY_BITS)
                .constant_f32("SKEW_LIMIT", params::SKEW_LIMIT)
                .constant("SORT_PAIRS_FROM_GATE", params::SORT_PAIRS_FROM_GATE)
                .constant("PAIRS_GATE_ONE", params::PAIRS_GATE_ONE)
                .constant("PAIRS_GATE_LIMIT", params::PAIRS_GATE_LIMIT)
                .constants(params::TraceLoop::ALL.map(|l| (l.glsl_name(), l as u32)))
                .constant("TRACE_LOOP_COUNT", params::TRACE_LOOP_COUNT)
                .constant("TRACE_STATUS_LOOPS", params::TRACE_STATUS_LOOPS)
                .render("params"),
        ),
        (
            "motion",
            Header::new()
                .push::<motion::GBufferTexel>()
                .push::<motion::MotionParams>()
                .push::<motion::HistoryParams>()
                .push::<motion::TaaParams>()
                .constant("REPROJECT_NONE", motion::REPROJECT_NONE)
                .constant("HISTORY_MIN_FRAMES", motion::HISTORY_MIN_FRAMES)
                .constant("HISTORY_MAX_FRAMES", motion::HISTORY_MAX_FRAMES)
                .constant("HISTORY_STRIP", motion::HISTORY_STRIP)
                .constant("HISTORY_COLUMNS", motion::HISTORY_COLUMNS)
                .constant_f32("REPROJECT_TIE_BIAS", motion::REPROJECT_TIE_BIAS)
                .constant_i32("REPROJECT_MAX_MOTION", motion::REPROJECT_MAX_MOTION)
                .constant_f32("SIMILAR_MIN_COS", motion::SIMILAR_MIN_COS)
                .constant_f32("SIMILAR_PLANE_DISTANCE", motion::SIMILAR_PLANE_DISTANCE)
                .constant_f32("TAA_ALPHA", motion::TAA_ALPHA)
                .constant_f32("TAA_SNAP", motion::TAA_SNAP)
                .render("motion"),
        ),
        ("sort_network", blueshift_layout::network::glsl_header()),
        (
            "view",
            Header::new()
                .push::<params::PresentParams>()
                .constant("PRESENT_FLAG_SPLIT", params::PRESENT_FLAG_SPLIT)
                .constant("PRESENT_FLAG_ERROR", params::PRESENT_FLAG_ERROR)
                .constant("PRESENT_FLAG_BGRA", params::PRESENT_FLAG_BGRA)
                .constant("PRESENT_DIVIDER_WIDTH", params::PRESENT_DIVIDER_WIDTH)
                .render("view"),
        ),
    ]
}

/// The generated-header directory of this workspace ([`blueshift_assets::workspace_path`]).
pub fn dir() -> PathBuf {
    blueshift_assets::workspace_path("shaders/include/generated", Path::is_dir)
}

/// Paths whose content differs from what the Rust structs generate now.
pub fn stale() -> Vec<PathBuf> {
    stale_in(&dir())
}

/// Like [`stale`], for headers in `dir`.
pub fn stale_in(dir: &Path) -> Vec<PathBuf> {
    all()
        .into_iter()
        .map(|(stem, text)| (dir.join(format!("{stem}.glsl")), text))
        .filter(|(p, text)| std::fs::read_to_string(p).ok().as_deref() != Some(text.as_str()))
        .map(|(p, _)| p)
        .collect()
}

/// Rewrites every generated header.
pub fn write_all() -> std::io::Result<()> {
    write_all_in(&dir())
}

/// Writes every generated header into `dir`.
pub fn write_all_in(dir: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for (stem, text) in all() {
        std::fs::write(dir.join(format!("{stem}.glsl")), text)?;
    }
    Ok(())
}
