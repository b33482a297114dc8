//! The `pdr` command-line tool: replay logs, benchmark the engine, serve the web app.
mod serve;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "pdr", version, about = "Pedestrian dead reckoning (Basso 2016/2021)")]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Serve the built web app: HTTP on localhost and HTTPS (self-signed) on all interfaces.
    Serve {
        /// Folder holding the built static site.
        #[arg(long, default_value = "dist")]
        root: PathBuf,
        /// HTTP port (localhost only).
        #[arg(long, default_value_t = 8080)]
        http_port: u16,
        /// HTTPS port (all interfaces).
        #[arg(long, default_value_t = 8443)]
        https_port: u16,
        /// Where to keep the self-signed certificate (default: the user's data directory).
        #[arg(long)]
        cert_dir: Option<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.cmd {
        Cmd::Serve { root, http_port, https_port, cert_dir } => serve::serve(serve::ServeOpts {
            root,
            http_port,
            https_port,
            cert_dir,
        }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("pdr: {e}");
            ExitCode::FAILURE
        }
    }
}
