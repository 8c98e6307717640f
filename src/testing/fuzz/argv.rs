//! The command lines of the `args` target: the commands of `limn` with their flags and
//! values (numbers, vectors, paths inside the fuzzer's folder, extreme numerals), generated
//! and then mutated, and the check that a command line names no path outside that folder.

use super::mutate::extreme_numerals;
use super::Rng;

/// The commands, with the flags each accepts (a flag name and whether it takes a value).
const COMMANDS: &[(&str, &[&str])] = &[
    ("info", &["--format", "--weld"]),
    (
        "silhouette",
        &[
            "--dir",
            "--eye",
            "--format",
            "--method",
            "--certificate",
            RUN,
        ],
    ),
    ("curves", &["--kind", "--format", "--dir", RUN]),
    ("events", &["--kinds", "--format", RUN]),
    ("hlr", &["--dir", "--eye", "--format", RUN]),
    (
        "visible",
        &["--dir", "--eye", "--format", "--cell-depth", "--cells", RUN],
    ),
    ("check", &["--format", "--threads"]),
    ("demo", &["--format"]),
];

/// Stands for the run options in [`COMMANDS`].
const RUN: &str = "RUN";

const RUN_FLAGS: &[&str] = &[
    "-o",
    "--output",
    "--force",
    "--threads",
    "--weld",
    "--max-depth",
    "--tol",
    "--abs-tol",
    "--time-limit",
];

/// Flags without a value.
const SWITCHES: &[&str] = &[
    "--force",
    "--abs-tol",
    "--cells",
    "--help",
    "-h",
    "--version",
    "-V",
];

const MODELS: &[&str] = &[
    "quad.bpt",
    "saddle.bpt",
    "tiny.json",
    "mesh.obj",
    "tiny.teaset",
    "tiny.igs",
    "bad.json",
    "empty.bpt",
    "missing.bpt",
    "sub",
    "sub/inner.bpt",
    "exists.txt",
    "",
    "-",
    "missing/x.json",
];

const OUTPUTS: &[&str] = &[
    "out.json",
    "out.svg",
    "out.txt",
    "out",
    "sub/out.obj",
    "exists.txt",
    "quad.bpt",
    "sub",
    "missing/out.json",
    "",
    "-",
    "./out.json",
];

const VECTORS: &[&str] = &[
    "1,2,3",
    "0,0,1",
    "0,0,0",
    "-0,0,0",
    "-0,-0,-0",
    "2,3,-2",
    "1/3,1/7,2",
    "0.5,0.5,0",
    "0.5,0.5,0.25",
    "1,1,0",
    "1e-400,1,1",
    "1e-400,1e-400,1e-400",
    "1e400,0,0",
    "1e10000,1,1",
    "1e-10000,0,0",
    "nan,1,1",
    "inf,0,0",
    "1,2",
    "1,2,3,4",
    "",
    ",,",
    " 1 , 2 , 3 ",
    "1;2;3",
    "x,y,z",
    "1,2,3,",
    "0,0,1e-300",
    "5e-324,0,0",
    "1e308,1e308,1e308",
];

fn values(flag: &str) -> &'static [&'static str] {
    match flag {
        "--dir" | "--eye" => VECTORS,
        "--format" => &["text", "json", "svg", "obj", "JSON", "xml", ""],
        "--method" => &["certified", "mesh", "srf-node", "srf_node", ""],
        "--kind" => &[
            "parabolic",
            "flecnodal",
            "bitangent",
            "Parabolic",
            "foo",
            "",
        ],
        "--kinds" => &[
            "parabolic,flecnodal,bitangent",
            "parabolic",
            "bitangent",
            "parabolic,parabolic",
            "",
            ",",
            "foo",
            "PARABOLIC",
            "parabolic,,flecnodal",
        ],
        "--tol" => &[
            "1e-3", "0.1", "0", "-0", "-1", "nan", "inf", "1e-300", "1e300", "5e-324", "1e400", "",
            "abc", "1/3",
        ],
        "--time-limit" => &[
            "0",
            "0.001",
            "1",
            "1e9",
            "999999999",
            "999999999.9",
            "1e308",
            "-1",
            "-0",
            "nan",
            "inf",
            "1e-300",
            "18446744073709551616",
            "",
        ],
        "--max-depth" => &["0", "1", "8", "40", "41", "-1", "4294967296", "", "24"],
        // Never many threads: a run with a million would exhaust the machine's processes.
        "--threads" => &["0", "1", "2", "3", "64", "-1", "", "x"],
        "--weld" => &[
            "exact", "EXACT", "0", "-1", "1e-3", "1e-9", "nan", "inf", "1e-400", "1e300", "",
        ],
        "--cell-depth" => &["0", "1", "4", "8", "14", "15", "-1", ""],
        "-o" | "--output" | "--certificate" => OUTPUTS,
        _ => &["", "1", "x"],
    }
}

const UNKNOWN: &[&str] = &[
    "--foo", "-x", "--", "-", "--dir=", "--tol=", "---", "--fo", "-oo",
];

/// A command line: its arguments, as bytes.
pub(super) type Argv = Vec<Vec<u8>>;

/// Builds a command line.
pub(super) fn generate(rng: &mut Rng) -> Argv {
    let mut args: Vec<String> = Vec::new();
    let (name, flags) = if rng.chance(1, 20) {
        (
            *rng.pick(&["", "help", "silhouettes", "--help", "-V", "INFO"]),
            &[][..],
        )
    } else {
        *rng.pick(COMMANDS)
    };
    if !name.is_empty() || rng.chance(1, 2) {
        args.push(name.to_string());
    }
    if name != "demo" {
        args.push(rng.pick(MODELS).to_string());
        if name == "check" {
            args.push(
                rng.pick(&["cert.json", "quad.bpt", "missing.json", "bad.json", ""])
                    .to_string(),
            );
        }
    }
    let mut all: Vec<&str> = Vec::new();
    for f in flags {
        if *f == RUN {
            all.extend(RUN_FLAGS);
        } else {
            all.push(f);
        }
    }
    let view = flags.contains(&"--eye");
    if view && rng.chance(9, 10) {
        let which = if rng.chance(3, 4) { "--dir" } else { "--eye" };
        push_flag(rng, &mut args, which);
    }
    if name == "curves" && rng.chance(9, 10) {
        push_flag(rng, &mut args, "--kind");
    }
    for f in &all {
        if rng.chance(1, 4) {
            push_flag(rng, &mut args, f);
        }
    }
    if rng.chance(1, 6) {
        // A flag of another command.
        let (_, others) = *rng.pick(COMMANDS);
        let f = *rng.pick(others);
        let f = if f == RUN { *rng.pick(RUN_FLAGS) } else { f };
        push_flag(rng, &mut args, f);
    }
    if rng.chance(1, 10) {
        args.push(rng.pick(UNKNOWN).to_string());
    }
    if rng.chance(1, 30) {
        args.push(rng.pick(&["--help", "-h", "--version", "-V"]).to_string());
    }
    let mut argv: Argv = args.into_iter().map(String::into_bytes).collect();
    for _ in 0..rng.below(4) {
        mutate_argv(rng, &mut argv);
    }
    argv
}

fn push_flag(rng: &mut Rng, args: &mut Vec<String>, flag: &str) {
    if SWITCHES.contains(&flag) {
        args.push(flag.to_string());
        return;
    }
    let value = rng.pick(values(flag)).to_string();
    if rng.chance(1, 4) && flag.starts_with("--") {
        args.push(format!("{flag}={value}"));
    } else {
        args.push(flag.to_string());
        args.push(value);
    }
}

fn mutate_argv(rng: &mut Rng, argv: &mut Argv) {
    let n = argv.len();
    match rng.below(9) {
        // Repeat an argument or a flag with its value.
        0 if n > 0 => {
            let i = rng.below(n);
            let k = (1 + rng.below(2)).min(n - i);
            let copy: Vec<_> = argv[i..i + k].to_vec();
            let at = rng.below(n + 1);
            argv.splice(at..at, copy);
        }
        1 if n > 0 => {
            argv.remove(rng.below(n));
        }
        2 if n > 1 => {
            let (i, j) = (rng.below(n), rng.below(n));
            argv.swap(i, j);
        }
        3 => {
            let at = rng.below(n + 1);
            argv.insert(at, rng.pick(&["", " ", "--", "-", "="]).as_bytes().to_vec());
        }
        // A value replaced by an extreme numeral, alone or as a coordinate.
        4 | 5 if n > 1 => {
            let i = 1 + rng.below(n - 1);
            let x = rng.pick(extreme_numerals()).clone();
            argv[i] = if rng.chance(1, 2) {
                x.into_bytes()
            } else {
                format!("{x},{x},1").into_bytes()
            };
        }
        6 if n > 0 => {
            // A byte changed (kept within the folder by `safe`).
            let i = rng.below(n);
            if !argv[i].is_empty() {
                let p = rng.below(argv[i].len());
                argv[i][p] = *rng.pick(b"-=,.0123456789eE/ \x00\xff\xc3x");
            }
        }
        7 => {
            // Invalid UTF-8, or a very long argument.
            let at = rng.below(n + 1);
            let arg = if rng.chance(1, 2) {
                b"--dir=\xff\xfe".to_vec()
            } else {
                "9".repeat(*rng.pick(&[300, 5000, 100_000])).into_bytes()
            };
            argv.insert(at, arg);
        }
        8 if n > 0 => {
            let i = rng.below(n);
            let mut joined = argv[i].clone();
            if i + 1 < n {
                joined.push(b'=');
                joined.extend_from_slice(&argv[i + 1]);
                argv.splice(i..i + 2, [joined]);
            }
        }
        _ => {}
    }
}

/// Whether every path a command line could name stays inside the fuzzer's folder: no
/// argument holds `..`, a NUL, `~`, or a `/` with nothing or a flag before it.
pub(super) fn safe(argv: &Argv) -> bool {
    argv.iter().all(|a| {
        if a.contains(&0) || a.windows(2).any(|w| w == b"..") || a.first() == Some(&b'~') {
            return false;
        }
        match a.iter().position(|&b| b == b'/') {
            None => true,
            Some(0) => false,
            Some(i) => a[..i]
                .iter()
                .all(|&b| b.is_ascii_alphanumeric() || b == b'_' || b == b'.'),
        }
    })
}
