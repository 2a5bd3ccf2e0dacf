//! `blueshift-tools`: see `tools/README.md`.

use clap::Parser;

fn main() -> anyhow::Result<()> {
    blueshift_tools::cli::run(blueshift_tools::cli::Cli::parse())
}
