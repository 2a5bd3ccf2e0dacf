//! Compiles every `shaders/**/*.comp` of the workspace, and every variant of
//! `blueshift_layout::variants` (a `.glsl` body with `#define`s before it), to SPIR-V
//! (Vulkan 1.2) with shaderc.
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

    // (name, source, file name for messages and includes): the hand-written shaders, then the
    // variants generated from blueshift-layout's list.
    let mut sources: Vec<(String, String, PathBuf)> = Vec::new();
    for file in &files {
        println!("cargo:rerun-if-changed={}", file.display());
        let rel = file.strip_prefix(&root).expect("under root");
        let name = rel.with_extension("").to_string_lossy().replace('\\', "/");
        let source = std::fs::read_to_string(file).expect("readable shader");
        sources.push((name, source, file.clone()));
    }
    for v in blueshift_layout::variants::shader_variants() {
        let body = root.join(v.body);
        let mut source = String::from("#version 460\n");
        for (key, value) in &v.defines {
            writeln!(source, "#define {key} {value}").expect("string");
        }
        let file_name = body.file_name().expect("a file").to_string_lossy();
        writeln!(source, "#include \"{file_name}\"").expect("string");
        // Named as if it sat next to its body, so that includes resolve from there.
        let file =
            body.with_file_name(format!("{}.comp", v.name.rsplit('/').next().expect("name")));
        sources.push((v.name, source, file));
    }

    let compiler = shaderc::Compiler::new().expect("shaderc compiler");
    let mut failed = Vec::new();
    let mut table = String::from(
        "/// (name, SPIR-V bytes) of every compiled shader.\npub static SHADERS: &[(&str, &[u8])] = &[\n",
    );
    for (name, source, file) in &sources {
        let mut opts = shaderc::CompileOptions::new().expect("shaderc options");
        opts.set_target_env(
            shaderc::TargetEnv::Vulkan,
            shaderc::EnvVersion::Vulkan1_2 as u32,
        );
        opts.set_optimization_level(shaderc::OptimizationLevel::Performance);
        // Keeps OpName / OpMemberName: passes bind resources by the names the SPIR-V declares.
        opts.set_generate_debug_info();
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
            source,
            shaderc::ShaderKind::Compute,
            &file.to_string_lossy(),
            "main",
            Some(&opts),
        ) {
            Ok(art) => {
                let spv = out_dir.join(format!("{}.spv", name.replace('/', "__")));
                let words = strip_sources(art.as_binary());
                std::fs::write(&spv, bytemuck_bytes(&words)).expect("write spv");
                writeln!(
                    table,
                    "    ({name:?}, include_bytes!({:?})),",
                    spv.display().to_string()
                )
                .expect("string");
            }
            Err(e) => failed.push(format!("{name}: {e}")),
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

/// The module without its source text and line table (OpSource*, OpString, OpLine, OpNoLine,
/// OpModuleProcessed), keeping OpName / OpMemberName: the names are what passes bind by, and
/// the embedded source is split into strings at byte boundaries that need not be UTF-8.
fn strip_sources(words: &[u32]) -> Vec<u32> {
    const DROP: [u32; 7] = [2, 3, 4, 7, 8, 317, 330];
    let mut out = words[..5].to_vec();
    let mut i = 5;
    while i < words.len() {
        let len = ((words[i] >> 16) as usize).max(1);
        if !DROP.contains(&(words[i] & 0xffff)) {
            out.extend_from_slice(&words[i..(i + len).min(words.len())]);
        }
        i += len;
    }
    out
}

fn bytemuck_bytes(words: &[u32]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_le_bytes()).collect()
}
