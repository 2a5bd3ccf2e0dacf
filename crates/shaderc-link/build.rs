//! Debian 12's `libshaderc_combined.a` (package libshaderc-dev) leaves glslang and SPIRV-Tools
//! symbols unresolved; the matching static archives come from glslang-dev and spirv-tools.
//! Linking them here lets every binary (including build scripts) that uses shaderc link.
fn main() {
    if std::env::var_os("SHADERC_LIB_DIR").is_some() {
        return; // a self-built shaderc brings its own archives
    }
    println!("cargo:rustc-link-search=native=/usr/lib/x86_64-linux-gnu");
    for lib in [
        "glslang",
        "SPIRV",
        "MachineIndependent",
        "GenericCodeGen",
        "OSDependent",
        "OGLCompiler",
        "HLSL",
        "glslang-default-resource-limits",
        "SPIRV-Tools-opt",
        "SPIRV-Tools",
    ] {
        println!("cargo:rustc-link-lib=static:-bundle={lib}");
    }
}
