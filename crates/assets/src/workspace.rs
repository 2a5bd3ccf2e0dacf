//! Finding a directory of this checkout at run time.
use std::path::{Path, PathBuf};

/// The directory `rel` of the workspace: the first one for which `is_it` holds above the
/// running cargo package, then above the current directory, else the one next to where this
/// crate was compiled. Cargo sets `CARGO_MANIFEST_DIR` at run time too, so a binary built in
/// another checkout sharing the target dir still finds this checkout's files.
pub fn workspace_path(rel: &str, is_it: impl Fn(&Path) -> bool) -> PathBuf {
    let starts = [
        std::env::var_os("CARGO_MANIFEST_DIR").map(PathBuf::from),
        std::env::current_dir().ok(),
    ];
    starts
        .into_iter()
        .flatten()
        .flat_map(|s| s.ancestors().map(|a| a.join(rel)).collect::<Vec<_>>())
        .find(|d| is_it(d))
        .unwrap_or_else(|| {
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../..")
                .join(rel)
        })
}
