//! The arguments the rendering commands share, and the typed value parsers behind them. The
//! names `--help` lists and error messages quote come from the tables the code parses with.
use crate::lighting::LightArgs;
use anyhow::{Result, bail};
use blueshift_render::{Method, MethodAssets, RenderConfig, SeedMap, default_assets_dir};
use blueshift_sampling::Sampler;
use blueshift_scene::Scene;
use clap::builder::{PossibleValue, TypedValueParser};
use std::ffi::OsStr;
use std::path::PathBuf;

/// A parser of a value from a string, with the error line's text.
type Parse<T> = fn(&str) -> Result<T, String>;

/// A clap value parser over a table of names: `--help` lists the names as the possible
/// values; an unknown name is one error line listing them.
#[derive(Clone)]
pub struct Named<T: 'static> {
    /// What the names name, for the error message.
    what: &'static str,
    /// (name, value) of everything `--help` lists.
    table: fn() -> Vec<(&'static str, T)>,
    /// Parses a value instead of the table (the spelled-out methods), with its own errors.
    parse: Option<Parse<T>>,
}

impl<T: Clone + Send + Sync + 'static> Named<T> {
    fn value(&self, s: &str) -> Result<T, String> {
        if s.is_empty() {
            return Err(format!("no {} named (an empty item?)", self.what));
        }
        if let Some(parse) = self.parse {
            return parse(s);
        }
        let table = (self.table)();
        let known: Vec<&str> = table.iter().map(|(n, _)| *n).collect();
        table
            .into_iter()
            .find(|(n, _)| *n == s)
            .map(|(_, v)| v)
            .ok_or_else(|| format!("unknown {} '{s}' (known: {})", self.what, known.join(", ")))
    }
}

impl<T: Clone + Send + Sync + 'static> TypedValueParser for Named<T> {
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<T, clap::Error> {
        let this = self.clone();
        // clap's parser of a `Fn(&str) -> Result` makes the error line (names the flag).
        (move |s: &str| this.value(s.trim())).parse_ref(cmd, arg, value)
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(
            (self.table)()
                .into_iter()
                .map(|(n, _)| PossibleValue::new(n)),
        ))
    }
}

/// A method preset or a spelled-out permutation (`sort-retarget:field=value,...`).
pub fn method_parser() -> Named<Method> {
    Named {
        what: "method",
        table: || Method::PRESETS.to_vec(),
        parse: Some(|s| s.parse()),
    }
}

/// What `eval` and `bench` compare: [`method_parser`]'s methods and the comparison baselines.
pub fn comparison_parser() -> Named<Method> {
    Named {
        what: "method",
        table: || [Method::PRESETS, Method::COMPARISONS].concat(),
        parse: Some(Method::parse_comparison),
    }
}

pub fn sampler_parser() -> Named<Sampler> {
    Named {
        what: "sampler",
        table: || Sampler::ALL.map(|s| (s.name(), s)).to_vec(),
        parse: None,
    }
}

pub fn seed_map_parser() -> Named<SeedMap> {
    Named {
        what: "seed map",
        table: || SeedMap::ALL.map(|m| (m.name(), m)).to_vec(),
        parse: None,
    }
}

pub fn env_sampling_parser() -> Named<blueshift_scene::EnvSampling> {
    Named {
        what: "environment sampling",
        table: || {
            blueshift_scene::EnvSampling::ALL
                .map(|m| (m.name(), m))
                .to_vec()
        },
        parse: None,
    }
}

/// The preset name of `m` (for a default value; clap keeps `&'static str` defaults).
pub fn preset_name(m: Method) -> &'static str {
    Method::PRESETS
        .iter()
        .find(|(_, p)| *p == m)
        .map_or("", |(n, _)| n)
}

pub fn method_help() -> String {
    format!(
        "A preset, or a spelled-out permutation PRESET:field=value,... (e.g. \
         sort-retarget:transport=none, the paper's sort alone) with {}",
        Method::fields_syntax()
    )
}

/// `--sampler`'s help: which sampler each preset uses unless told.
fn sampler_help() -> String {
    let mut uses: Vec<(Sampler, Vec<&str>)> = Vec::new();
    for (name, m) in Method::PRESETS {
        let s = m.default_sampler();
        match uses.iter_mut().find(|(u, _)| *u == s) {
            Some((_, names)) => names.push(name),
            None => uses.push((s, vec![name])),
        }
    }
    // The sampler most presets use is named once, for "the others".
    uses.sort_by_key(|(_, names)| std::cmp::Reverse(names.len()));
    let each: Vec<String> = uses[1..]
        .iter()
        .map(|(s, names)| format!("{} for {}", s.name(), names.join(", ")))
        .collect();
    format!(
        "Seeded sampler [default: the method's: {}, {} for the others; hbo19 with \
         --initial-seeds hbo19]",
        each.join(", "),
        uses[0].0.name()
    )
}

/// The scene, its light and what every method run shares: `render`, `bench`, `soak`, `view`
/// and `eval`.
#[derive(clap::Args, Debug, Clone)]
pub struct SceneArgs {
    #[arg(long, default_value = "cornell-box", help = format!(
        "glTF/GLB file, or a bundled preset: {}", blueshift_scene::presets::PRESETS.join(", ")))]
    pub scene: String,
    #[command(flatten)]
    pub lights: LightArgs,
    /// Directory with masks and retarget tables.
    #[arg(long)]
    pub assets: Option<PathBuf>,
    /// Sorting block edge (2..=8) of sort-retarget and its spelled-out forms [default: 4];
    /// sort-cycle and sort-grid-adaptive sort 8x8 blocks of their own.
    #[arg(long)]
    pub block: Option<u32>,
    #[arg(long, value_parser = sampler_parser(), help = sampler_help())]
    pub sampler: Option<Sampler>,
    /// Frame-0 seed map of sort / sort-retarget: random, or hbo19 (HBO+19 tile positions with
    /// the hbo19 sampler, so that they start from blue noise; the hbo19 method always uses them).
    #[arg(long, default_value = SeedMap::Random.name(), value_parser = seed_map_parser())]
    pub initial_seeds: SeedMap,
    /// Let the scene's buffer and image URIs lead outside its directory (`..`, absolute
    /// paths, `file:` URIs, symlinks out): refused by default, since a downloaded glTF file
    /// could otherwise read any file the user can.
    #[arg(long)]
    pub allow_outside_paths: bool,
}

impl SceneArgs {
    /// Loads the scene lit as the flags say, printing its warnings (one line each).
    pub fn load_scene(&self) -> Result<Scene> {
        let spec = self.scene.as_str();
        let path = self.scene_path();
        let (environment, map_warning) = self.lights.source()?;
        let opts = blueshift_scene::LoadOptions {
            environment,
            quiet: true,
            allow_outside_paths: self.allow_outside_paths,
            ..Default::default()
        };
        let looks_like_preset = !spec.contains(['/', '.']);
        let mut scene = match Scene::load_with(&path, &opts) {
            Err(blueshift_scene::SceneError::NotFound { .. }) if looks_like_preset => bail!(
                "scene '{spec}' is neither a file nor a preset (presets: {})",
                blueshift_scene::presets::PRESETS.join(", ")
            ),
            // The scene error names the file.
            r => r?,
        };
        // The scene then holds the only reference to the map: scaling or rotating it below
        // changes it in place instead of copying it (`Arc::make_mut`).
        drop(opts);
        let dark = self.lights.apply(&mut scene)?;
        for w in scene.warnings.iter().chain(&map_warning).chain(&dark) {
            eprintln!("warning: {w}");
        }
        Ok(scene)
    }

    pub fn load_assets(&self) -> Result<MethodAssets> {
        Ok(MethodAssets::load(
            &self.assets.clone().unwrap_or_else(default_assets_dir),
        )?)
    }

    /// The file `--scene` names: a bundled preset from `scenes/` of `--assets` or of the
    /// default assets directory (`--assets` may hold masks only), else the path as given.
    pub fn scene_path(&self) -> PathBuf {
        let spec = self.scene.as_str();
        if spec.contains(['/', '.']) {
            return PathBuf::from(spec);
        }
        let preset = |dir: PathBuf| dir.join("scenes").join(format!("{spec}.gltf"));
        self.assets
            .iter()
            .cloned()
            .chain([default_assets_dir()])
            .map(preset)
            .find(|p| p.exists())
            .unwrap_or_else(|| PathBuf::from(spec))
    }
}

/// One method on a scene: `render`, `bench`, `soak` and `view` (`eval` takes lists of methods,
/// sample counts and bounces instead, parsed by the same parsers). A command whose defaults
/// differ sets them with `mut_arg`.
#[derive(clap::Args, Debug, Clone)]
pub struct MethodArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[arg(long, default_value_t = Method::DEFAULT, value_parser = method_parser(),
          help = method_help())]
    pub method: Method,
    #[arg(long, default_value_t = 256)]
    pub width: u32,
    #[arg(long, default_value_t = 256)]
    pub height: u32,
    /// Samples per pixel per frame.
    #[arg(long, default_value_t = 1)]
    pub spp: u32,
    /// Path vertices after the camera (1 = direct light only).
    #[arg(long, default_value_t = 8)]
    pub bounces: u32,
}

impl MethodArgs {
    /// The renderer's configuration (checked against the device when the renderer is made).
    pub fn config(&self) -> RenderConfig {
        RenderConfig {
            spp: self.spp,
            bounces: self.bounces,
            block: self.scene.block,
            method: self.method,
            sampler: self.scene.sampler,
            seed_map: self.scene.initial_seeds,
            ..RenderConfig::new(self.width, self.height)
        }
    }
}
