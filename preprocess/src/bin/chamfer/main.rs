//! `chamfer`: bake meshes into `.chamfer` edge assets, inspect, render and draw them (SVG), and write
//! marks back into meshes.

mod annotate;
mod bake;
mod demo;
mod draw;
mod flags;
mod inspect;
mod memory;
mod render;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Chamfer bakes the feature edges of meshes (OBJ, glTF/GLB, PLY) into compact `.chamfer` assets
/// for real-time edge rendering with wgpu.
#[derive(Parser)]
#[command(name = "chamfer", version, about, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    Bake(bake::BakeArgs),
    Inspect(inspect::InspectArgs),
    Demo(demo::DemoArgs),
    Annotate(annotate::AnnotateArgs),
    Render(render::RenderArgs),
    Draw(draw::DrawArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Bake(args) => bake::run(&args),
        Command::Inspect(args) => inspect::run(&args),
        Command::Demo(args) => demo::run(&args),
        Command::Annotate(args) => annotate::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Draw(args) => draw::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader went away (`| head`): nothing more is wanted, as for any command-line tool.
        Err(e)
            if e.downcast_ref::<StdoutError>()
                .is_some_and(StdoutError::is_closed_pipe) =>
        {
            ExitCode::SUCCESS
        }
        Err(e) => {
            warn(format_args!("error: {}", describe(&e)));
            ExitCode::FAILURE
        }
    }
}

/// Standard output could not be written (`> /dev/full`, a closed pipe).
#[derive(Debug, thiserror::Error)]
#[error("cannot write to standard output: {0}")]
pub struct StdoutError(std::io::Error);

impl StdoutError {
    fn is_closed_pipe(&self) -> bool {
        self.0.kind() == std::io::ErrorKind::BrokenPipe
    }
}

/// Writes `text` and a newline to standard output, flushed, reporting failure instead of
/// panicking as `println!` does.
pub fn say(text: impl std::fmt::Display) -> anyhow::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    writeln!(out, "{text}")
        .and_then(|()| out.flush())
        .map_err(|e| StdoutError(e).into())
}

/// Writes a line to standard error; if even that fails there is nobody left to tell.
pub fn warn(text: impl std::fmt::Display) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "{text}");
}

/// The error and its causes on one line, skipping a cause whose text the message already quotes
/// (the library's errors name their cause in their own message).
pub fn describe(error: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in error.chain() {
        let cause = cause.to_string();
        // Parser messages can span lines; the first line says what is wrong.
        let cause = cause.lines().next().unwrap_or_default();
        if !text.contains(cause) {
            if !text.is_empty() {
                text.push_str(": ");
            }
            text.push_str(cause);
        }
    }
    text
}
