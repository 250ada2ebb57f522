//! The `--rerun` and `--rerun-connect` options every recording command shares.

use std::path::PathBuf;

use clap::Args;

use super::Recording;

/// Where to send a Rerun recording.
#[derive(Debug, Clone, Default, Args)]
pub struct RerunArgs {
    /// Record for the Rerun viewer into this .rrd file (`rerun FILE.rrd` opens it).
    #[arg(long, value_name = "FILE.rrd", conflicts_with = "rerun_connect")]
    pub rerun: Option<PathBuf>,
    /// Stream the recording to a running Rerun viewer, e.g. `rerun+http://127.0.0.1:9876/proxy`.
    #[arg(long, value_name = "ADDR")]
    pub rerun_connect: Option<String>,
}

impl RerunArgs {
    /// Whether a recording was asked for.
    pub fn wanted(&self) -> bool {
        self.rerun.is_some() || self.rerun_connect.is_some()
    }

    /// Opens the asked recording (none when not asked), named `what` in the viewer.
    #[cfg(feature = "rerun")]
    pub fn open(&self, what: &str) -> anyhow::Result<Option<Recording>> {
        use super::sdk;
        use anyhow::Context;
        let builder =
            || sdk::RecordingStreamBuilder::new("knotlab").recording_name(format!("knotlab {what}"));
        if let Some(path) = &self.rerun {
            if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
                std::fs::create_dir_all(parent)
                    .with_context(|| format!("--rerun {}: creating {}", path.display(), parent.display()))?;
            }
            let stream =
                builder().save(path).map_err(|e| anyhow::anyhow!("--rerun {}: {e}", path.display()))?;
            return Ok(Some(stream));
        }
        if let Some(addr) = &self.rerun_connect {
            let stream = builder()
                .connect_grpc_opts(addr.clone())
                .map_err(|e| anyhow::anyhow!("--rerun-connect {addr}: {e}"))?;
            return Ok(Some(stream));
        }
        Ok(None)
    }

    /// Without the `rerun` feature: a clear refusal when a recording is asked for.
    #[cfg(not(feature = "rerun"))]
    pub fn open(&self, _what: &str) -> anyhow::Result<Option<Recording>> {
        if self.wanted() {
            anyhow::bail!(
                "--rerun/--rerun-connect: this knotlab was built without the `rerun` feature \
                 (build with default features, or `--features rerun`)"
            );
        }
        Ok(None)
    }
}

/// Ends a recording: everything logged reaches the file or the viewer before the command exits.
pub fn finish(recording: Option<Recording>) -> anyhow::Result<()> {
    #[cfg(feature = "rerun")]
    if let Some(stream) = recording {
        stream.flush_blocking().map_err(|e| anyhow::anyhow!("finishing the Rerun recording: {e}"))?;
    }
    #[cfg(not(feature = "rerun"))]
    let _ = recording;
    Ok(())
}
