//! Viewer output: the Rerun sink of SPEC 6 ([`rerun_sink`]). Its colours
//! and outlines are the SVG's ([`scen_runner::palette`]), so both show a
//! plan in the same colour and a world with the same shapes.

#[cfg(feature = "viewer")]
pub mod rerun_sink;

use std::path::PathBuf;

#[cfg(feature = "viewer")]
pub(crate) use scen_runner::palette::*;

/// Where [`stream`] sends a run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ViewerTarget {
    /// Write an `.rrd` file (`--save`).
    Save(PathBuf),
    /// Start the viewer, the `rerun` executable on PATH (`--spawn`). When a
    /// process already listens on the default port, it is used instead.
    Spawn,
    /// Stream to a running viewer (`--connect [ADDR]`). `ADDR` is
    /// `HOST:PORT` or a full `rerun+http://HOST:PORT/proxy` URL; the default
    /// is Rerun 0.36's `rerun::DEFAULT_CONNECT_URL`,
    /// `rerun+http://127.0.0.1:9876/proxy`.
    Connect(Option<String>),
}

/// Why a run could not be streamed. The messages are complete sentences
/// for a warning: they say what to do.
#[derive(Debug, thiserror::Error)]
// Without the viewer, only `NotBuilt` is made.
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub enum ViewerError {
    #[error("cannot write the Rerun recording `{}`: {message}", path.display())]
    Save { path: PathBuf, message: String },
    #[error(
        "cannot start the Rerun viewer: `rerun` is not on PATH; \
         install it with `pip install rerun-sdk==0.36.3`"
    )]
    ViewerMissing,
    #[error("cannot start the Rerun viewer: {0}")]
    Spawn(String),
    #[error(
        "`{0}` is not a Rerun viewer address; \
         use `HOST:PORT` or `rerun+http://HOST:PORT/proxy`"
    )]
    BadAddress(String),
    #[error(
        "no Rerun viewer is listening at `{url}`; \
         start one with `rerun`, or use `--spawn` or `--save FILE.rrd`"
    )]
    Unreachable { url: String },
    #[error("streaming to the Rerun viewer failed: {0}")]
    Stream(String),
    #[error(
        "this `scen` was built without the viewer (cargo feature `viewer`): \
         `--save`, `--spawn` and `--connect` are not available; install the \
         default build (`cargo install --path .`), or draw with `--svg`"
    )]
    NotBuilt,
}

/// Whether this build can stream to the viewer (the cargo feature `viewer`,
/// on by default; `cargo install --no-default-features` builds without the
/// Rerun SDK, about three times faster).
pub const VIEWER_BUILT: bool = cfg!(feature = "viewer");

/// Streams the run to `target` (see [`rerun_sink::stream`]); without the
/// viewer in the build, says so.
pub fn stream(report: &crate::run::RunReport, target: &ViewerTarget) -> Result<(), ViewerError> {
    #[cfg(feature = "viewer")]
    {
        rerun_sink::stream(report, target)
    }
    #[cfg(not(feature = "viewer"))]
    {
        let _ = (report, target);
        Err(ViewerError::NotBuilt)
    }
}
