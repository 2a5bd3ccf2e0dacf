//! Atomic image output: write to a temporary file in the same directory, then rename, so a
//! failed or interrupted run never leaves a half-written file under the final name; and
//! [`Staged`] output, whose files appear only once the whole run has succeeded (`render`,
//! `eval`; `bench` prints its results only at the end for the same reason).
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};

/// The one atomic writer of the workspace (temporary file in the same directory, then
/// rename).
pub use blueshift_assets::write_atomic;

/// Encodes RGBA8 pixels as PNG (in memory).
pub fn png_rgba8(width: u32, height: u32, rgba: &[u8]) -> Result<Vec<u8>> {
    let img = image::RgbaImage::from_raw(width, height, rgba.to_vec()).context("pixel count")?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)?;
    Ok(out.into_inner())
}

/// Encodes linear RGB (alpha ignored) as a float EXR (in memory).
pub fn exr_rgb32f(width: u32, height: u32, rgba: &[[f32; 4]]) -> Result<Vec<u8>> {
    let data: Vec<f32> = rgba.iter().flat_map(|p| [p[0], p[1], p[2]]).collect();
    let img = image::Rgb32FImage::from_raw(width, height, data).context("pixel count")?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::OpenExr)?;
    Ok(out.into_inner())
}

/// An output directory from [`prepare_dir`]. If this run created it and it is still empty when
/// dropped (the run failed before writing anything), it is removed again.
#[must_use = "dropping the guard removes the directory it created while it is empty"]
#[derive(Debug)]
pub struct OutputDir {
    created: Option<PathBuf>,
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if let Some(dir) = &self.created {
            let _ = std::fs::remove_dir(dir); // fails, as it should, unless empty
        }
    }
}

/// Creates `dir` (and parents) and checks it is writable, naming it on failure.
pub fn prepare_dir(dir: &Path) -> Result<OutputDir> {
    let created = (!dir.exists()).then(|| dir.to_path_buf());
    std::fs::create_dir_all(dir)
        .with_context(|| format!("cannot create output directory {}", dir.display()))?;
    let guard = OutputDir { created };
    let probe = dir.join(format!(".blueshift-write-test.{}", std::process::id()));
    std::fs::write(&probe, b"")
        .with_context(|| format!("output directory {} is not writable", dir.display()))?;
    let _ = std::fs::remove_file(probe);
    Ok(guard)
}

/// The files of a run (`render`'s frames; `eval`'s report, figures and `frames/`), written into a hidden
/// temporary directory inside the output directory and moved into it by [`Staged::commit`]
/// once the run has succeeded. A run that fails before (a lost device at frame 40) leaves the
/// output directory as it found it: the temporary directory is removed, and so is the output
/// directory if the run created it.
#[must_use = "dropping it without commit() removes what was written"]
#[derive(Debug)]
pub struct Staged {
    // Fields drop in this order: the temporary directory first, then (if it is empty by then
    // and this run created it) the output directory.
    tmp: tempfile::TempDir,
    dir: PathBuf,
    _out: OutputDir,
}

impl Staged {
    /// [`prepare_dir`] `dir`, then a temporary directory inside it.
    pub fn new(dir: &Path) -> Result<Self> {
        let out = prepare_dir(dir)?;
        let tmp = tempfile::Builder::new()
            .prefix(".blueshift-partial-")
            .tempdir_in(dir)
            .with_context(|| format!("output directory {} is not writable", dir.display()))?;
        Ok(Self {
            tmp,
            dir: dir.to_path_buf(),
            _out: out,
        })
    }

    /// Where the run writes its files (named as they will be in the output directory).
    pub fn path(&self) -> &Path {
        self.tmp.path()
    }

    /// Moves what was written into the output directory: a file replaces the file of its name,
    /// a directory is moved whole where the name is free, else merged into the directory there
    /// the same way (`eval`'s `frames/`). Every name is checked before anything is moved, so a
    /// directory where a file goes, or a file where a directory goes, leaves the output
    /// directory as it was.
    pub fn commit(self) -> Result<()> {
        let mut moves = Vec::new();
        plan_moves(self.tmp.path(), &self.dir, &mut moves)?;
        for (from, to) in &moves {
            std::fs::rename(from, to).with_context(|| format!("cannot write {}", to.display()))?;
        }
        Ok(())
    }
}

/// Appends the renames that move the entries of `from` into `to` (in name order), or fails
/// on the first name that `to` holds as the other kind (file or directory).
fn plan_moves(from: &Path, to: &Path, moves: &mut Vec<(PathBuf, PathBuf)>) -> Result<()> {
    let reading = "reading the temporary output";
    let mut entries = Vec::new();
    for e in std::fs::read_dir(from).context(reading)? {
        let e = e.context(reading)?;
        entries.push((e.file_name(), e.file_type().context(reading)?.is_dir()));
    }
    entries.sort();
    for (name, is_dir) in entries {
        let (src, dst) = (from.join(&name), to.join(&name));
        let there = std::fs::symlink_metadata(&dst).ok().map(|m| m.is_dir());
        match (is_dir, there) {
            (false, Some(true)) => bail!(
                "cannot write {}: a directory of that name is in the way",
                dst.display()
            ),
            (true, Some(false)) => bail!(
                "cannot write {}/: a file of that name is in the way",
                dst.display()
            ),
            (true, Some(true)) => plan_moves(&src, &dst, moves)?,
            _ => moves.push((src, dst)),
        }
    }
    Ok(())
}
