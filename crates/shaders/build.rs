//! Compiles every `shaders/**/*.comp` of the workspace to SPIR-V (Vulkan 1.2) with shaderc.
//! `#include "x.glsl"` resolves next to the including file, then in `shaders/include/`.
//! Errors fail the build with `file:line: message` lines from glslang.
use blueshift_shaderc_link as shaderc;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<_> = rd.filter_map(|e| e.ok()).map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            collect(&p, out);
        } else if p.extension().is_some_and(|e| e == "comp") {
            out.push(p);
        }
    }
}

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets this"));
    let root = manifest
        .join("../../shaders")
        .canonicalize()
        .expect("shaders/ exists at the workspace root");
    let include_dir = root.join("include");
    let out_dir = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets this"));
    println!("cargo:rerun-if-changed={}", root.display());

    let mut files = Vec::new();
    collect(&root, &mut files);

    let compiler = shaderc::Compiler::new().expect("shaderc compiler");
    let mut failed = Vec::new();
    let mut table = String::from(
        "/// (name, SPIR-V bytes) of every compiled shader.\npub static SHADERS: &[(&str, &[u8])] = &[\n",
    );
    for file in &files {
        println!("cargo:rerun-if-changed={}", file.display());
        let rel = file.strip_prefix(&root).expect("under root");
        let name = rel.with_extension("").to_string_lossy().replace('\\', "/");
        let source = std::fs::read_to_string(file).expect("readable shader");
        let mut opts = shaderc::CompileOptions::new().expect("shaderc options");
        opts.set_target_env(
            shaderc::TargetEnv::Vulkan,
            shaderc::EnvVersion::Vulkan1_2 as u32,
        );
        opts.set_optimization_level(shaderc::OptimizationLevel::Performance);
        let inc = include_dir.clone();
        opts.set_include_callback(move |requested, _ty, requester, _depth| {
            let here = Path::new(requester).parent().map(Path::to_path_buf).unwrap_or_default();
            for base in [here, inc.clone()] {
                let p = base.join(requested);
                if let Ok(content) = std::fs::read_to_string(&p) {
                    println!("cargo:rerun-if-changed={}", p.display());
                    return Ok(shaderc::ResolvedInclude {
                        resolved_name: p.to_string_lossy().into_owned(),
                        content,
                    });
                }
            }
            Err(format!("cannot find include \"{requested}\" (searched next to {requester} and in shaders/include)"))
        });
        match compiler.compile_into_spirv(
            &source,
            shaderc::ShaderKind::Compute,
            &file.to_string_lossy(),
            "main",
            Some(&opts),
        ) {
            Ok(art) => {
                let spv = out_dir.join(format!("{}.spv", name.replace('/', "__")));
                std::fs::write(&spv, art.as_binary_u8()).expect("write spv");
                writeln!(
                    table,
                    "    ({name:?}, include_bytes!({:?})),",
                    spv.display().to_string()
                )
                .expect("string");
            }
            Err(e) => failed.push(e.to_string()),
        }
    }
    table.push_str("];\n");
    if !failed.is_empty() {
        for f in &failed {
            eprintln!("{f}");
        }
        eprintln!("error: {} shader(s) failed to compile", failed.len());
        std::process::exit(1);
    }
    std::fs::write(out_dir.join("shaders.rs"), table).expect("write table");
}
