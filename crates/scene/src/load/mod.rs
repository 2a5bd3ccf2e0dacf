//! glTF 2.0 loading: `.gltf` (embedded base64 or external buffers) and `.glb`.
//!
//! What is read: every TRIANGLES primitive of every mesh in the node tree of the default scene
//! (else the first scene), flattened to world space (normals by the inverse transpose; winding
//! flipped under mirroring transforms so the face normal keeps pointing out of the front face);
//! metallic-roughness materials with base color / metallic-roughness / emissive textures and
//! KHR_materials_emissive_strength; KHR_materials_specular factors (its textures are skipped);
//! the first perspective camera; the environment.
//!
//! Lights: emissive materials and `KHR_lights_punctual` (see `lights`). glTF has no
//! environment light, so it is taken from [`LoadOptions::environment`] if set, else from the
//! scene's `extras` `{"blueshift_environment": [r, g, b]}` (linear radiance), else black (the
//! caller may then light a dark scene with [`Scene::light_if_dark`]).
//!
//! Bad data: a missing file, malformed JSON/GLB (GLB headers are checked before the reader
//! sees them, see `glb`), a version other than 2.x, a required extension the loader lacks,
//! spec violations the reader misses (`precheck`), missing, empty or short buffers, unreadable
//! accessors, out-of-range vertex indices, positions that are non-finite or of magnitude
//! [`MAX_COORDINATE`] or more, and lights whose radiance overflows f32 are errors
//! ([`SceneError`]). So are a node graph that is not a tree and a scene over [`LoadBudget`]:
//! both are checked from the JSON before the scene is expanded (`graph`, `budget`), so memory
//! stays proportional to the file and to the scene; sparse accessors stay sparse
//! (`accessor`), and images no material uses are not read (`images`).
//!
//! Files: every file opened (the scene, buffers, images) must be a regular file, checked
//! before it is opened (a FIFO would block, a device never end; see [`crate::open_regular`]);
//! a buffer is read up to its `byteLength` and no further. External URIs must stay inside the
//! scene file's directory unless [`LoadOptions::allow_outside_paths`] is set (`uri`).
//!
//! Zero-area triangles are skipped and counted in one warning, and so are triangles equal bit
//! for bit to an earlier one (`dedup`: a pile of copies would cost every ray through it a
//! test per copy, past the trace pass's loop guard). Unsupported content
//! (non-triangle modes, normal/occlusion maps, texture transforms, unusable lights, other
//! extensions, missing or undecodable images or ones whose header declares more texels than
//! the budget has left, ...) is skipped with one warning line per kind, with a count, in
//! [`Scene::warnings`](crate::Scene::warnings), also printed once to stderr.

mod accessor;
mod budget;
mod dedup;
mod glb;
mod graph;
mod guard;
mod images;
mod lights;
mod material;
mod precheck;
mod primitive;
mod uri;
mod warnings;

pub use budget::LoadBudget;
pub(crate) use warnings::Warnings;

use crate::scene::{Image, Material, Scene, Texture};
use crate::{Camera, Result, SceneError};
use glam::{Mat3, Mat4, Vec3};
use gltf::buffer;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// An environment given by the caller: a constant or a map.
#[derive(Clone, Debug, PartialEq)]
pub enum EnvironmentSource {
    /// Constant linear radiance.
    Constant(Vec3),
    /// An equirectangular map ([`crate::EnvMap::load`]).
    Map(Arc<crate::EnvMap>),
}

/// Options for [`Scene::load_with`].
#[derive(Clone, Debug, Default)]
pub struct LoadOptions {
    /// Overrides the environment from the file.
    pub environment: Option<EnvironmentSource>,
    /// Do not print warnings to stderr (they are still collected in `Scene::warnings`).
    pub quiet: bool,
    /// The most the scene may hold (counted before it is read).
    pub budget: LoadBudget,
    /// Read buffer and image files outside the scene file's directory: absolute paths,
    /// `file:` URIs, `..` that climbs out of it, symlinks whose target lies outside it. Off by
    /// default, such a URI is an error ([`SceneError::OutsidePath`]).
    pub allow_outside_paths: bool,
}

/// The scene `extras` key holding the environment radiance `[r, g, b]`.
pub const ENVIRONMENT_EXTRAS_KEY: &str = "blueshift_environment";

/// Vertex coordinates (in the file and in world space) must be smaller than this in magnitude:
/// larger ones overflow the tracer's f32 arithmetic (squared extents, edge vectors) or lose
/// the scene to rounding, and render a wrong image.
pub const MAX_COORDINATE: f32 = 1e13;

/// The largest scene file read (a GLB's length field is 32 bits).
const MAX_SCENE_BYTES: u64 = u32::MAX as u64;

/// Deepest node hierarchy accepted.
const MAX_NODE_DEPTH: usize = 256;

/// Shared state while walking one document.
pub(crate) struct Ctx<'a> {
    pub path: &'a Path,
    /// The scene directory, against which external URIs are resolved (`None`: from memory).
    pub base: Option<&'a Path>,
    pub allow_outside: bool,
    pub buffers: &'a [buffer::Data],
    pub warnings: Warnings,
    pub zero_area: usize,
}

pub(crate) fn load(path: &Path, options: &LoadOptions) -> Result<Scene> {
    let io = |source| SceneError::Io {
        path: path.to_path_buf(),
        source,
    };
    let bytes = match crate::read_regular(path, MAX_SCENE_BYTES) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(SceneError::NotFound {
                path: path.to_path_buf(),
            });
        }
        other => other.map_err(io)?,
    };
    let base = path.parent().unwrap_or(Path::new("."));
    load_bytes(path, &bytes, Some(base), options)
}

/// Loads from bytes (`.gltf` JSON or `.glb`); `name` only labels errors. External URIs are
/// resolved against `base`; with `None` they are an error.
pub(crate) fn load_bytes(
    name: &Path,
    bytes: &[u8],
    base: Option<&Path>,
    options: &LoadOptions,
) -> Result<Scene> {
    let path = name;
    let mut scene = guard::catch_panics(path, || load_inner(path, bytes, base, options))?;
    match &options.environment {
        Some(EnvironmentSource::Constant(c)) => {
            scene.environment = *c;
            scene.environment_map = None;
        }
        Some(EnvironmentSource::Map(m)) => {
            scene.environment = Vec3::ZERO;
            scene.environment_map = Some(m.clone());
        }
        None => {}
    }
    if !options.quiet {
        for w in &scene.warnings {
            eprintln!("warning: {}: {w}", path.display());
        }
    }
    Ok(scene)
}

fn load_inner(
    path: &Path,
    bytes: &[u8],
    base: Option<&Path>,
    options: &LoadOptions,
) -> Result<Scene> {
    let budget = &options.budget;
    let parse = |source| SceneError::Parse {
        path: path.to_path_buf(),
        source,
    };
    // A UTF-8 byte-order mark before the JSON is allowed (the reader would stop at it).
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let glb = glb::check(bytes).map_err(|problem| SceneError::Glb {
        path: path.to_path_buf(),
        problem,
    })?;
    let trailing = bytes.len() - glb.len();
    let gltf::Gltf { document, blob } = gltf::Gltf::from_slice_without_validation(glb)
        .map_err(|e| precheck::version_of_unreadable(path, glb).unwrap_or_else(|| parse(e)))?;
    precheck::spec(path, document.as_json())?;
    let problems = precheck::check(document.as_json());
    if !problems.is_empty() {
        return Err(parse(gltf::Error::Validation(problems)));
    }
    let document = gltf::Document::from_json(document.into_json()).map_err(parse)?;
    let buffers = load_buffers(path, &document, base, blob, options.allow_outside_paths)?;
    let mut ctx = Ctx {
        path,
        base,
        allow_outside: options.allow_outside_paths,
        buffers: &buffers,
        warnings: Warnings::default(),
        zero_area: 0,
    };
    if trailing > 0 {
        ctx.warnings.warn("glb-trailing", || {
            format!("{trailing} bytes after the GLB's declared total length are ignored")
        });
    }
    warn_extensions(&document, &mut ctx.warnings);

    let gltf_scene = document
        .default_scene()
        .or_else(|| document.scenes().next())
        .ok_or_else(|| SceneError::EmptyScene {
            path: path.to_path_buf(),
            reason: "the file has no scenes".into(),
        })?;
    // The graph and the counts first: nothing below allocates more than they allow.
    let nodes = graph::check(path, &document, &gltf_scene, MAX_NODE_DEPTH)?;
    budget::count(path, &document, &nodes, budget)?;

    let (images, image_map) = images::load(&document, budget.texels, &mut ctx)?;
    let all_textures = material::load_textures(&document, &image_map);
    let mut textures = Vec::new();
    let mut materials =
        material::load_materials(&document, &all_textures, &mut textures, &mut ctx)?;
    let images = compact_images(images, &mut textures);
    let default_material = materials.len() as u32;
    materials.push(Material {
        name: Some("default".into()),
        ..Material::default()
    });

    let environment = environment_from_extras(gltf_scene.extras(), &mut ctx.warnings);

    let mut triangles = Vec::new();
    let mut camera = None;
    let mut punctual = Vec::new();
    // Each node once (the graph check guarantees it), in the file's order.
    let mut stack: Vec<(gltf::Node, Mat4)> =
        gltf_scene.nodes().map(|n| (n, Mat4::IDENTITY)).collect();
    stack.reverse();
    while let Some((node, parent)) = stack.pop() {
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if !world.is_finite() {
            ctx.warnings.warn("transform", || {
                format!(
                    "node {} has a non-finite transform; it and its children are skipped",
                    node.index()
                )
            });
            continue;
        }
        if node.skin().is_some() {
            ctx.warnings.warn("skin", || {
                "skinning ignored: meshes are drawn in bind pose".into()
            });
        }
        if let Some(light) = lights::read(path, &document, &node, &world, &mut ctx.warnings)? {
            punctual.push(light);
        }
        if let Some(cam) = node.camera() {
            read_camera(&cam, &world, &mut camera, &mut ctx.warnings);
        }
        if let Some(mesh) = node.mesh() {
            let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
            for prim in mesh.primitives() {
                primitive::read(
                    &mut ctx,
                    &mesh,
                    &prim,
                    &world,
                    &normal_matrix,
                    default_material,
                    &mut triangles,
                )?;
            }
        }
        let children: Vec<_> = node.children().collect();
        for child in children.into_iter().rev() {
            stack.push((child, world));
        }
    }

    if ctx.zero_area > 0 {
        let n = ctx.zero_area;
        ctx.warnings.warn("zero-area", || {
            format!(
                "skipped {} zero-area triangles",
                warnings::thousands(n as u64)
            )
        });
    }
    dedup::drop_duplicates(&mut triangles, &mut ctx.warnings);
    // The scene is kept while it renders: not the up to 2x of a grown Vec.
    triangles.shrink_to_fit();
    if triangles.is_empty() {
        return Err(SceneError::EmptyScene {
            path: path.to_path_buf(),
            reason: format!(
                "scene {} has no triangle primitives with non-zero area",
                gltf_scene.index()
            ),
        });
    }
    Ok(Scene {
        source: PathBuf::from(path),
        triangles,
        materials,
        textures,
        images: images.into(),
        camera,
        environment,
        environment_map: None,
        environment_sampling: crate::EnvSampling::Importance,
        lights: punctual,
        warnings: ctx.warnings.finish(),
    })
}

/// Keeps only the images some material texture uses, remapping the textures.
fn compact_images(images: Vec<Image>, textures: &mut [Texture]) -> Vec<Image> {
    let mut remap: Vec<Option<u32>> = vec![None; images.len()];
    let mut slots: Vec<Option<Image>> = images.into_iter().map(Some).collect();
    let mut kept = Vec::new();
    for t in textures.iter_mut() {
        let i = t.image as usize;
        if let Some(img) = slots[i].take() {
            remap[i] = Some(kept.len() as u32);
            kept.push(img);
        }
        t.image = remap[i].unwrap_or_default();
    }
    kept
}

/// Loads every buffer, naming the one that fails. A buffer declaring `byteLength` N gets its
/// first N bytes: a longer file is not read further, a shorter (or empty) one is an error.
fn load_buffers(
    path: &Path,
    document: &gltf::Document,
    base: Option<&Path>,
    mut blob: Option<Vec<u8>>,
    allow_outside: bool,
) -> Result<Vec<buffer::Data>> {
    let mut out = Vec::new();
    for b in document.buffers() {
        let uri = match b.source() {
            buffer::Source::Bin => "GLB binary chunk".to_string(),
            buffer::Source::Uri(u) if u.starts_with("data:") => "embedded data URI".to_string(),
            buffer::Source::Uri(u) => u.to_string(),
        };
        let err = |problem: String| SceneError::Buffer {
            path: path.to_path_buf(),
            index: b.index(),
            uri: uri.clone(),
            problem,
        };
        let length = b.length();
        let short = |got: usize, what: &str| {
            err(blueshift_assets::files::short_of(
                got as u64,
                length as u64,
                what,
            ))
        };
        let mut data = match b.source() {
            buffer::Source::Bin => match blob.take() {
                Some(bin) if bin.len() < length => {
                    return Err(short(bin.len(), "the GLB BIN chunk"));
                }
                Some(bin) => bin,
                None => return Err(err("it has no uri, and no GLB BIN chunk holds it".into())),
            },
            buffer::Source::Uri(u) => match uri::locate(u, base, allow_outside) {
                Ok(None) => {
                    let data = buffer::Data::from_source(b.source(), base)
                        .map_err(|e| err(format!("cannot load: {e}")))?;
                    if data.len() < length {
                        return Err(short(data.len(), "the data URI"));
                    }
                    data.0
                }
                Ok(Some(file)) => blueshift_assets::files::read_prefix(&file, length as u64)
                    .map_err(|e| err(format!("cannot load: {}: {e}", file.display())))?,
                Err(uri::Refused::Outside { dir, reason }) => {
                    return Err(SceneError::OutsidePath {
                        path: path.to_path_buf(),
                        what: format!("buffer {}", b.index()),
                        uri,
                        dir,
                        reason,
                    });
                }
                Err(uri::Refused::Other(e)) => return Err(err(format!("cannot load: {e}"))),
            },
        };
        // As the reader pads them.
        while data.len() % 4 != 0 {
            data.push(0);
        }
        out.push(buffer::Data(data));
    }
    Ok(out)
}

/// One warning line per reason an extension is ignored (a file may list thousands).
fn warn_extensions(document: &gltf::Document, warnings: &mut Warnings) {
    for ext in document.extensions_used() {
        let (kind, reason) = match ext {
            "KHR_materials_emissive_strength"
            | "KHR_materials_specular"
            | "KHR_lights_punctual" => {
                continue;
            }
            "KHR_texture_transform" => (
                "ext-transform",
                "ignored: textures are sampled without the transform",
            ),
            e if e.starts_with("KHR_materials_") => {
                ("ext-materials", "ignored: only metallic-roughness is used")
            }
            _ => ("ext-unsupported", "not supported, ignored"),
        };
        warnings.warn_item(
            kind,
            &format!("extensions {reason}"),
            || ext.to_string(),
            |ext| format!("extension {ext} {reason}"),
        );
    }
}

fn environment_from_extras(extras: &gltf::json::Extras, warnings: &mut Warnings) -> Vec3 {
    let Some(raw) = extras else {
        return Vec3::ZERO;
    };
    // Only the key is parsed into values: the others stay raw, so a sibling nested deeper than
    // serde_json's recursion limit (128) cannot make the whole `extras` unreadable.
    type Raw<'a> = std::collections::HashMap<String, &'a serde_json::value::RawValue>;
    let Ok(entries) = serde_json::from_str::<Raw>(raw.get()) else {
        return Vec3::ZERO;
    };
    let Some(raw_env) = entries.get(ENVIRONMENT_EXTRAS_KEY) else {
        return Vec3::ZERO;
    };
    let env = serde_json::from_str::<serde_json::Value>(raw_env.get())
        .unwrap_or_else(|_| serde_json::Value::String(raw_env.get().chars().take(80).collect()));
    let rgb: Option<Vec<f32>> = env.as_array().map(|a| {
        a.iter()
            .filter_map(|v| v.as_f64().map(|x| x as f32))
            .collect()
    });
    match rgb {
        Some(c) if c.len() == 3 && c.iter().all(|x| x.is_finite() && *x >= 0.0) => {
            Vec3::new(c[0], c[1], c[2])
        }
        _ => {
            warnings.warn("environment", || {
                format!(
                    "scene extras {ENVIRONMENT_EXTRAS_KEY} must be [r, g, b] with finite \
                     non-negative numbers, got {env}; using black"
                )
            });
            Vec3::ZERO
        }
    }
}

fn read_camera(
    cam: &gltf::Camera,
    world: &Mat4,
    camera: &mut Option<Camera>,
    warnings: &mut Warnings,
) {
    match cam.projection() {
        gltf::camera::Projection::Perspective(p) => {
            if camera.is_some() {
                return; // the first camera wins
            }
            let position = world.transform_point3(Vec3::ZERO);
            let forward = world.transform_vector3(Vec3::NEG_Z);
            let up = world.transform_vector3(Vec3::Y);
            let yfov = p.yfov();
            if forward.length() > 0.0
                && up.length() > 0.0
                && yfov > 0.0
                && yfov < std::f32::consts::PI
            {
                *camera = Some(Camera {
                    position,
                    target: position + forward.normalize(),
                    up: up.normalize(),
                    yfov,
                });
            } else {
                warnings.warn("camera", || {
                    format!("camera {} is degenerate and ignored", cam.index())
                });
            }
        }
        gltf::camera::Projection::Orthographic(_) => {
            warnings.warn("ortho", || {
                "orthographic cameras are not supported and ignored".into()
            });
        }
    }
}
