//! The `pdr` command-line tool. It is native only: built for wasm32 (as `cargo test --target
//! wasm32-unknown-unknown` does for every target) it is an empty program.
//! Here: the `out!` macro and the modules; `cli` parses the command line and dispatches.
//! May import: the `pdr` library and its own subcommand modules.

/// `println!` that ends the program quietly when standard output is closed (`pdr … | head`)
/// instead of panicking, as command-line tools do.
#[cfg(not(target_arch = "wasm32"))]
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if let Err(e) = writeln!(std::io::stdout().lock(), $($arg)*) {
            if e.kind() == std::io::ErrorKind::BrokenPipe {
                std::process::exit(0);
            }
            eprintln!("pdr: cannot write to standard output: {e}");
            std::process::exit(1);
        }
    }};
}

#[cfg(not(target_arch = "wasm32"))]
mod bench;
#[cfg(not(target_arch = "wasm32"))]
mod calibrate;
#[cfg(not(target_arch = "wasm32"))]
mod calibrate_loo;
#[cfg(not(target_arch = "wasm32"))]
mod cli;
#[cfg(not(target_arch = "wasm32"))]
mod demo;
#[cfg(not(target_arch = "wasm32"))]
mod eval;
#[cfg(not(target_arch = "wasm32"))]
mod read;
#[cfg(not(target_arch = "wasm32"))]
mod run;
#[cfg(not(target_arch = "wasm32"))]
mod serve;
#[cfg(not(target_arch = "wasm32"))]
mod settings_args;
#[cfg(not(target_arch = "wasm32"))]
mod simcheck;
#[cfg(not(target_arch = "wasm32"))]
mod simulate;

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    cli::main()
}

#[cfg(target_arch = "wasm32")]
fn main() {}
