//! Reference images: Owen-scrambled Sobol at >= 1024 spp, cached on disk under a key of scene,
//! camera path, resolution, bounces, spp, primary-ray placement (jittered or pixel centres) and
//! the code of the path tracer variants that render references (the renderer version). A cache
//! file whose header does not describe exactly the job's reference (size, key, length) is a
//! miss with a warning: the reference is rendered again and the file replaced atomically.
use crate::output::write_atomic;
use anyhow::{Context, Result, bail};
use blueshift_analysis::luminance;
use blueshift_device::Device;
use blueshift_layout::variants::TraceVariant;
use blueshift_render::{CameraPath, Method, MethodAssets, RenderConfig, Renderer};
use blueshift_sampling::Sampler;
use blueshift_scene::Scene;
use indicatif::{ProgressBar, ProgressStyle};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Samples per pixel per reference frame; references accumulate `spp / REF_CHUNK` frames.
const REF_CHUNK: u32 = 64;
/// Version 2 added the key to the header.
const MAGIC: &[u8; 8] = b"BSREF02\0";

/// Linear RGB + luminance per pixel.
#[derive(Debug, Clone)]
pub struct Image {
    pub w: u32,
    pub h: u32,
    pub px: Vec<[f32; 4]>,
}

impl Image {
    /// The `w x h` window at column `x0` (pans crop one wide reference).
    pub fn crop(&self, x0: u32, w: u32, h: u32) -> Image {
        let px = (0..h)
            .flat_map(|y| (x0..x0 + w).map(move |x| (x, y)))
            .map(|(x, y)| self.px[(y * self.w + x) as usize])
            .collect();
        Image { w, h, px }
    }
    /// Rec.709 luminance of the rgb channels (not the fourth channel, which is the sorting key).
    pub fn luminance(&self) -> Vec<f32> {
        self.px
            .iter()
            .map(|p| luminance([p[0], p[1], p[2]]))
            .collect()
    }
}

/// References for every frame of a camera path.
pub enum References {
    /// One image for all frames (static camera).
    Single(Image),
    /// A wide image; frame t is the window at column `columns[t]` (integer pans).
    Pan { wide: Image, columns: Vec<u32> },
    /// One image per frame.
    PerFrame(Vec<Image>),
}

impl References {
    pub fn frame(&self, t: u32, w: u32, h: u32) -> Image {
        match self {
            References::Single(i) => i.clone(),
            References::Pan { wide, columns } => wide.crop(columns[t as usize], w, h),
            References::PerFrame(v) => v[t as usize].clone(),
        }
    }
}

/// What a reference depends on.
pub struct RefJob<'a> {
    pub dev: &'a Device,
    pub scene: &'a Scene,
    pub scene_bytes: &'a [u8],
    pub assets: &'a MethodAssets,
    pub width: u32,
    pub height: u32,
    pub bounces: u32,
    pub spp: u32,
    pub frames: u32,
    pub path: &'a CameraPath,
    pub cache: &'a Path,
    pub no_jitter: bool,
}

/// A hash of the canonical SPIR-V ([`blueshift_shaders::canonical_words`]) of every variant a
/// reference can be rendered with (Sobol, no mask). Only code those variants run changes it:
/// another sampler's or a mask mode's code, comments and line numbers do not, so work on the
/// methods keeps the (slow) references.
fn path_tracer_version() -> &'static [u8] {
    static VERSION: OnceLock<Vec<u8>> = OnceLock::new();
    VERSION.get_or_init(|| {
        let mut h = Sha256::new();
        let reference_variants = TraceVariant::all()
            .into_iter()
            .filter(|v| v.sampler == Sampler::Sobol && !v.mask && !v.loop_stats);
        for v in reference_variants {
            let words = blueshift_shaders::spirv(&v.shader()).unwrap_or_default();
            // A module that does not parse (never, for our own) still keys by its raw words.
            let canonical = blueshift_shaders::canonical_words(&words).unwrap_or(words);
            h.update(bytemuck::cast_slice::<u32, u8>(&canonical));
        }
        h.finalize().to_vec()
    })
}

fn key(job: &RefJob, what: &str) -> String {
    let mut h = Sha256::new();
    h.update(job.scene_bytes);
    // The lighting the flags add (environment, intensity, rotation, the default light).
    let s = job.scene;
    h.update(format!(
        "{:?}|{:?}|{:?}",
        s.environment, s.lights, s.environment_sampling
    ));
    if let Some(m) = &s.environment_map {
        h.update(format!("{}x{}|{}", m.width, m.height, m.rotation));
        h.update(bytemuck::cast_slice::<glam::Vec3, u8>(&m.texels));
    }
    h.update(path_tracer_version());
    // A jittered reference is the pixel's area average, a centred one its centre value: they
    // differ at every edge, so they must never share a cache entry.
    let rays = if job.no_jitter { "centres" } else { "jitter" };
    h.update(format!(
        "{what}|{}x{}|b{}|spp{}|{rays}|v{}",
        job.width,
        job.height,
        job.bounces,
        job.spp,
        env!("CARGO_PKG_VERSION")
    ));
    h.finalize()
        .iter()
        .take(KEY_LEN / 2)
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Bytes of a cache file: [`MAGIC`], width and height (u32 little-endian), the cache key
/// ([`KEY_LEN`] ASCII hex digits: the file's own name), then width x height texels of 4 f32.
const HEADER_LEN: usize = 8 + 4 + 4 + KEY_LEN;
/// Hex digits of a cache key ([`key`]).
const KEY_LEN: usize = 24;

/// The length of the cache file of a `w x h` reference; `None` if that does not fit a u64.
fn file_len(w: u32, h: u32) -> Option<u64> {
    u64::from(w)
        .checked_mul(u64::from(h))?
        .checked_mul(16)?
        .checked_add(HEADER_LEN as u64)
}

/// What the cache holds for one reference.
#[derive(Debug)]
enum Cached {
    Hit(Image),
    Missing,
    /// A file that is not this job's reference (truncated, another size, another version or
    /// key, not a regular file): why, for the warning. It is rendered again and replaced.
    Unusable(String),
}

/// Reads the cached `w x h` reference of cache key `key` from `path`. The header must
/// describe exactly this job's reference; a file of any other length is not read in full.
fn load(path: &Path, key: &str, w: u32, h: u32) -> Cached {
    let Some(want) = file_len(w, h) else {
        return Cached::Unusable(format!("a {w}x{h} reference does not fit in a file"));
    };
    // A regular file of at most the expected length: a FIFO would block, a huge file cost.
    match blueshift_assets::files::read_regular(path, want) {
        Ok(bytes) => parse(&bytes, key, w, h, want).map_or_else(Cached::Unusable, Cached::Hit),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Cached::Missing,
        Err(e) => Cached::Unusable(e.to_string()),
    }
}

/// The reference in `bytes` (a whole cache file) if its header matches the job.
fn parse(bytes: &[u8], key: &str, w: u32, h: u32, want: u64) -> Result<Image, String> {
    let Some(header) = bytes.get(..HEADER_LEN) else {
        return Err(format!(
            "it has {} bytes, fewer than the {HEADER_LEN}-byte header",
            bytes.len()
        ));
    };
    let (magic, rest) = header.split_at(MAGIC.len());
    if magic != MAGIC {
        return Err(
            "it is not a reference cache file of this version (no BSREF02 header)".to_string(),
        );
    }
    let (size, file_key) = rest.split_at(8);
    let word = |b: &[u8]| u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
    let (fw, fh) = (word(&size[..4]), word(&size[4..]));
    if (fw, fh) != (w, h) {
        return Err(format!(
            "its header declares a {fw}x{fh} image, but this reference is {w}x{h}"
        ));
    }
    if file_key != key.as_bytes() {
        return Err("its header names another cache key".to_string());
    }
    if bytes.len() as u64 != want {
        return Err(format!(
            "it has {} bytes, but this {w}x{h} reference needs {want} (truncated?)",
            bytes.len()
        ));
    }
    Ok(Image {
        w,
        h,
        px: bytemuck::pod_collect_to_vec(&bytes[HEADER_LEN..]),
    })
}

fn save(path: &Path, key: &str, img: &Image) -> Result<()> {
    let mut bytes = MAGIC.to_vec();
    bytes.extend(img.w.to_le_bytes());
    bytes.extend(img.h.to_le_bytes());
    bytes.extend(key.as_bytes());
    bytes.extend(bytemuck::cast_slice::<[f32; 4], u8>(&img.px));
    Ok(write_atomic(path, &bytes)?)
}

/// Renders (or loads from cache) one reference image.
fn render_one(
    job: &RefJob,
    what: &str,
    w: u32,
    frame: u32,
    view: (u32, u32),
    bar: &ProgressBar,
) -> Result<Image> {
    let (_, base) = job.path.view_window(job.frames, job.width, job.height);
    let key = key(job, &format!("{what}|w{w}|f{frame}|view{view:?}{base:?}"));
    let file: PathBuf = job.cache.join(format!("{key}.ref"));
    match load(&file, &key, w, job.height) {
        Cached::Hit(img) => {
            bar.inc(job.spp as u64);
            return Ok(img);
        }
        Cached::Missing => {}
        Cached::Unusable(why) => bar.suspend(|| {
            eprintln!(
                "warning: reference cache {}: {why}; rendering the reference again",
                file.display()
            );
        }),
    }
    let cfg = RenderConfig {
        spp: REF_CHUNK.min(job.spp),
        bounces: job.bounces,
        method: Method::Sobol,
        sampler: Some(Sampler::Sobol),
        view_size: Some(view),
        no_jitter: job.no_jitter,
        ..RenderConfig::new(w, job.height)
    };
    let mut r = Renderer::new(job.dev, job.scene, job.assets, cfg.clone())?;
    r.set_camera(job.path.camera(&job.scene.camera_or_default(), frame));
    let o = job.path.view_offset(frame);
    r.set_view_offset((base.0 + o.0, base.1 + o.1));
    for _ in 0..job.spp.div_ceil(cfg.spp) {
        r.render_frame()?;
        bar.inc(cfg.spp as u64);
    }
    let acc = r.read_accum()?;
    let img = Image {
        w,
        h: job.height,
        px: acc,
    };
    std::fs::create_dir_all(job.cache)
        .with_context(|| format!("creating cache {}", job.cache.display()))?;
    save(&file, &key, &img)?;
    Ok(img)
}

/// All references of a camera path.
pub fn references(job: &RefJob) -> Result<References> {
    if job.spp == 0 {
        bail!("--reference-spp must be positive");
    }
    if job.spp < 1024 {
        eprintln!(
            "warning: --reference-spp {} is below 1024 (docs/results.md): reference noise inflates every metric",
            job.spp
        );
    }
    let per_frame = |n: u32| n as u64 * job.spp as u64;
    let label = job.path.label();
    let (view, _) = job.path.view_window(job.frames, job.width, job.height);
    let make_bar = |total: u64| {
        let bar = ProgressBar::new(total);
        bar.set_style(
            ProgressStyle::with_template("reference {msg} {bar:30} {percent}% eta {eta}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar.set_message(format!("{label} b{}", job.bounces));
        bar
    };
    Ok(match job.path {
        CameraPath::Static => {
            let bar = make_bar(per_frame(1));
            let r = References::Single(render_one(job, &label, job.width, 0, view, &bar)?);
            bar.finish_and_clear();
            r
        }
        CameraPath::Pan { px_per_frame } if px_per_frame.fract() == 0.0 && *px_per_frame >= 0.0 => {
            let wide_w = view.0;
            let columns = (0..job.frames)
                .map(|t| job.path.view_offset(t).0 as u32)
                .collect();
            let bar = make_bar(per_frame(1));
            let wide = render_one(job, &label, wide_w, 0, view, &bar)?;
            bar.finish_and_clear();
            References::Pan { wide, columns }
        }
        _ => {
            let bar = make_bar(per_frame(job.frames));
            let v = (0..job.frames)
                .map(|f| render_one(job, &label, job.width, f, view, &bar))
                .collect::<Result<Vec<_>>>()?;
            bar.finish_and_clear();
            References::PerFrame(v)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cache file as [`save`] writes it, with the header's size replaced by `(w, h)`.
    fn file(key: &str, (w, h): (u32, u32), texels: usize) -> Vec<u8> {
        let img = Image {
            w,
            h,
            px: vec![[0.5; 4]; texels],
        };
        let dir = tempfile::tempdir().expect("tempdir");
        let p = dir.path().join("x.ref");
        save(&p, key, &img).expect("save");
        std::fs::read(p).expect("read")
    }

    #[test]
    fn a_cache_file_is_used_only_if_its_header_describes_the_job() {
        let key = "0123456789abcdef01234567";
        assert_eq!(key.len(), KEY_LEN);
        let want = file_len(8, 8).expect("fits");
        let good = file(key, (8, 8), 64);
        assert_eq!(good.len() as u64, want);
        let img = parse(&good, key, 8, 8, want).expect("a hit");
        assert_eq!((img.w, img.h, img.px.len()), (8, 8, 64));
        // Width x height overflows u32 (once a panic), the same texel count in another shape
        // (once accepted), another key, a truncated body, a header cut short.
        let reasons = [
            (
                file(key, (65536, 65536), 64),
                "declares a 65536x65536 image",
            ),
            (file(key, (4, 16), 64), "declares a 4x16 image"),
            (
                file("fedcba9876543210fedcba98", (8, 8), 64),
                "another cache key",
            ),
            (good[..good.len() - 1].to_vec(), "(truncated?)"),
            (good[..HEADER_LEN - 1].to_vec(), "fewer than the"),
            (b"BSREF01\0".to_vec(), "fewer than the"),
        ];
        for (bytes, reason) in reasons {
            let e = parse(&bytes, key, 8, 8, want).expect_err(reason);
            assert!(e.contains(reason), "{reason}: {e}");
        }
        let mut old = good.clone();
        old[..8].copy_from_slice(b"BSREF01\0");
        let e = parse(&old, key, 8, 8, want).expect_err("old version");
        assert!(
            e.contains("not a reference cache file of this version"),
            "{e}"
        );
        assert_eq!(file_len(u32::MAX, u32::MAX), None);
    }
}
