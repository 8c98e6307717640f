//! The `limn` command line: a thin layer over the library, in three parts: `args` (what the
//! user typed, checked), `commands` (one function per command, each a call of the library's
//! front door), `output` (where and how results are written). Every command that computes
//! something can print JSON (`--format json`) whose field names are a public contract,
//! documented per command in `docs/commands/`.

mod args;
mod commands;
mod output;

use crate::cli::args::{Cli, Command};
use clap::Parser;
use std::io::Write;
use std::process::ExitCode;

/// The tolerance of `limn demo`, relative to the bounding-box diagonal.
pub const DEMO_TOLERANCE: f64 = 1e-3;

/// The view direction of `limn demo`.
pub const DEMO_DIRECTION: &str = "1,2,3";

/// The view direction of the demo's hidden-line drawing (from above, in front of the spout).
pub const DEMO_HLR_DIRECTION: &str = "2,3,-2";

/// The Newell teapot (32 bicubic patches), embedded so that `limn demo` needs no files.
pub const EMBEDDED_TEAPOT: &str = crate::TEAPOT;

/// A failure of a command: the message, and the exit code (2 for bad input or arguments).
#[derive(Debug)]
pub struct CliError {
    /// One line: the file, the place and what is wrong.
    pub message: String,
    /// The process exit code.
    pub code: u8,
}

impl CliError {
    fn input(message: impl Into<String>) -> CliError {
        CliError {
            message: message.into(),
            code: 2,
        }
    }
}

/// Runs the command line `args` (including the program name), writing results to `out`.
///
/// # Errors
/// [`CliError`] with exit code 2 on bad arguments or bad input files.
pub fn run<I, T>(args: I, out: &mut dyn Write) -> Result<(), CliError>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = Cli::try_parse_from(args).map_err(|e| {
        use clap::error::ErrorKind;
        match e.kind() {
            // --help and --version: the full text, on stdout, success.
            ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => CliError {
                message: e.render().to_string().trim_end().to_string(),
                code: 0,
            },
            ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => CliError::input(
                "no command given: try `limn demo`, `limn info MODEL`, or `limn --help`",
            ),
            // Anything else: clap's first line ("error: ..."), as one line, exit 2.
            _ => {
                // clap's message up to the usage block, joined into one line.
                let text = e.render().to_string();
                let message: Vec<&str> = text
                    .lines()
                    .map(str::trim)
                    .take_while(|l| {
                        !l.starts_with("Usage:")
                            && !l.starts_with("tip:")
                            && !l.starts_with("For more")
                    })
                    .filter(|l| !l.is_empty())
                    .collect();
                let joined = message.join(" ");
                let first = joined.strip_prefix("error: ").unwrap_or(&joined);
                CliError::input(format!("{first} (see `limn --help`)"))
            }
        }
    })?;
    match cli.command {
        Command::Info(args) => commands::info_command(args, out),
        Command::Silhouette(args) => commands::silhouette_command(args, out),
        Command::Curves(args) => commands::curves_command(args, out),
        Command::Events(args) => commands::events_command(args, out),
        Command::Hlr(args) => commands::hlr_command(args, out),
        Command::Visible(args) => commands::visible_command(args, out),
        Command::Check(args) => commands::check_command(args, out),
        Command::Demo(args) => commands::demo_command(args, out),
    }
}

/// The entry point of the `limn` binary: runs, prints errors on stderr as one line, and
/// returns the exit code (2 for bad input or arguments).
pub fn main() -> ExitCode {
    let mut stdout = std::io::stdout().lock();
    match run(std::env::args_os(), &mut stdout) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.code == 0 => {
            let _ = writeln!(stdout, "{}", e.message);
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("limn: {}", e.message);
            ExitCode::from(e.code)
        }
    }
}
