//! The `limn` command; all logic is in [`limn::cli`].

fn main() -> std::process::ExitCode {
    limn::cli::main()
}
