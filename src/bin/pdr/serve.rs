//! `pdr serve`: placeholder, replaced by the dev-server implementation.
use std::path::PathBuf;

/// Options of `pdr serve`.
#[derive(Debug, Clone)]
pub struct ServeOpts {
    /// Folder to serve (the built static site).
    pub root: PathBuf,
    /// Plain HTTP port, bound on localhost only.
    pub http_port: u16,
    /// HTTPS port, bound on all interfaces.
    pub https_port: u16,
    /// Where the self-signed certificate is kept (outside the repository).
    pub cert_dir: Option<PathBuf>,
}

/// Serves `opts.root` until interrupted.
pub fn serve(_opts: ServeOpts) -> Result<(), String> {
    Err("not implemented yet".into())
}
