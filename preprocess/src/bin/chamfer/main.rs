//! `chamfer`: bake meshes into `.chamfer` edge assets, inspect, render and draw them (SVG), and write
//! marks back into meshes.

mod annotate;
mod bake;
mod demo;
mod draw;
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
        Err(e) => {
            eprintln!("error: {}", describe(&e));
            ExitCode::FAILURE
        }
    }
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
