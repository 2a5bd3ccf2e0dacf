//! `scene`: write the bundled glTF scene presets.

/// `scene` flags.
#[derive(Debug, clap::Args)]
pub struct SceneArgs {
    /// Preset name, or `all`.
    #[arg(long, default_value = "all")]
    pub name: String,
    /// Output directory.
    #[arg(long, default_value = "assets/scenes")]
    pub out: std::path::PathBuf,
}

/// Writes the bundled scene presets.
pub(crate) fn scene(a: &SceneArgs) -> anyhow::Result<()> {
    let names: Vec<&str> = if a.name == "all" {
        blueshift_scene::presets::PRESETS.to_vec()
    } else {
        vec![a.name.as_str()]
    };
    std::fs::create_dir_all(&a.out)?;
    for n in names {
        let p = blueshift_scene::presets::write_preset(n, &a.out)?;
        println!("wrote {}", p.display());
    }
    Ok(())
}
