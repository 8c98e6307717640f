//! Fuzzing of the model readers: `limn::io::read_model_bytes` on random bytes, random
//! model-like text and mutated real fixtures, for each format and for auto-detection. Every
//! call must return `Ok` or `Err` (never panic), finish quickly, and an `Err` must be one line
//! naming the file and a place.
//!
//! Cases: `limn::testing_cases(64)` per property (`LIMN_PROPTEST_CASES` to change it).
//! Failures are kept in `proptest-regressions/reader_fuzz.txt` and replayed first.

use limn::io::{read_model_bytes, Place, ReadError};
use limn::model::{Format, Model, ModelInfo, WeldTolerance};
use limn::testing::fuzz::mutate::{iges_fields, line_spans, number_tokens, replace_iges_field};
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use std::sync::mpsc;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// Every forced format, and `None` (detect from the content).
const FORMATS: [Option<Format>; 7] = [
    None,
    Some(Format::Json),
    Some(Format::Bpt),
    Some(Format::Teaset),
    Some(Format::Iges),
    Some(Format::Obj),
    Some(Format::Step),
];

/// A hang guard: no read of a file of a few tens of kilobytes may take this long.
const DEADLINE: Duration = Duration::from_secs(20);

fn config() -> ProptestConfig {
    ProptestConfig {
        // Integration tests have no lib.rs above them, so proptest's default would put the
        // regressions next to this file; keep them with the crate's others.
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/proptest-regressions/reader_fuzz.txt"
        )))),
        // A failing case shrinks for at most a minute.
        max_shrink_time: 60_000,
        ..ProptestConfig::with_cases(limn::testing_cases(64))
    }
}

/// A real model file to mutate.
struct Fixture {
    name: &'static str,
    bytes: Vec<u8>,
    format: Format,
}

fn fixtures() -> &'static [Fixture] {
    static FIXTURES: OnceLock<Vec<Fixture>> = OnceLock::new();
    FIXTURES.get_or_init(|| {
        let root = env!("CARGO_MANIFEST_DIR");
        let file = |name: &'static str, format: Format| Fixture {
            name,
            bytes: std::fs::read(format!("{root}/{name}"))
                .unwrap_or_else(|e| panic!("fixture {name}: {e}")),
            format,
        };
        let all = vec![
            Fixture {
                name: "fuzz.json",
                bytes: limn::testing::fuzz::json_sample().into_bytes(),
                format: Format::Json,
            },
            file("fixtures/bezier/teapot.bpt", Format::Bpt),
            file("fixtures/bezier/newell_teaset/teacup", Format::Teaset),
            file("fixtures/iges/forIGES/128-000.igs", Format::Iges),
            // 124 transformation matrices.
            file("fixtures/iges/forIGES/surf128.igs", Format::Iges),
            // A 144 trimmed surface.
            file("fixtures/iges/occt/OCC26138_Torus.igs", Format::Iges),
            // 510 faces.
            file("fixtures/iges/occt/OCC8842_cone_Ideas.igs", Format::Iges),
            file(
                "fixtures/meshes/keenan/spot/spot_control_mesh.obj",
                Format::Obj,
            ),
            // A closed B-rep of planes, and B-spline faces with pcurves and seams.
            file("fixtures/step/occt-written/box.stp", Format::Step),
            file(
                "fixtures/step/occt-written/OCC8842_cylinder_Ideas.stp",
                Format::Step,
            ),
        ];
        // The unmutated fixtures must read, or the mutations test little.
        for f in &all {
            if let Err(e) = read_model_bytes(f.name, &f.bytes, Some(f.format)) {
                panic!("fixture {} does not read: {e}", f.name);
            }
        }
        all
    })
}

/// Reads on a separate thread, failing the test on a panic (with its message) or when the
/// read runs past [`DEADLINE`]. Checks the shape of any error.
fn read_checked(name: &str, bytes: &[u8], format: Option<Format>) -> Result<Model, ReadError> {
    let (tx, rx) = mpsc::channel();
    let (owned_name, owned) = (name.to_string(), bytes.to_vec());
    let start = Instant::now();
    let handle = std::thread::spawn(move || {
        let r = read_model_bytes(&owned_name, &owned, format);
        let _ = tx.send(r);
    });
    let result = match rx.recv_timeout(DEADLINE) {
        Ok(r) => r,
        Err(mpsc::RecvTimeoutError::Timeout) => panic!(
            "read_model_bytes({name:?}, {} bytes, {format:?}) ran for more than {DEADLINE:?}",
            bytes.len()
        ),
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            let payload = handle
                .join()
                .expect_err("the reader thread ended without a result");
            let msg = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            panic!("read_model_bytes({name:?}, {format:?}) panicked: {msg}");
        }
    };
    let elapsed = start.elapsed();
    if let Err(e) = &result {
        let text = e.to_string();
        assert!(
            text.starts_with(&format!("{name}: ")),
            "the error does not start with the file name: {text:?}"
        );
        assert!(!e.message.trim().is_empty(), "an empty message: {text:?}");
        assert!(
            !text.contains('\n') && !text.contains('\r'),
            "the error is not one line: {text:?}"
        );
        assert!(
            text.chars().count() < 1000,
            "the error is {} characters long",
            text.chars().count()
        );
        match &e.place {
            Place::Line(l) | Place::LineColumn(l, _) => assert!(*l >= 1, "line 0 in {text:?}"),
            Place::Entity { de, .. } => assert!(*de >= 1, "entity 0 in {text:?}"),
            Place::Named(s) => assert!(!s.is_empty(), "an empty place in {text:?}"),
            Place::Instance { kind, .. } => assert!(!kind.is_empty(), "no entity name in {text:?}"),
            Place::File | Place::Patch { .. } => {}
        }
    }
    if let Ok(m) = &result {
        // What `limn info` does next, with exact welding (see tests/bad_input.rs for the
        // default IGES welding).
        let _ = ModelInfo::of(name, m, WeldTolerance::Exact);
    }
    let total = start.elapsed();
    assert!(
        total < DEADLINE,
        "read {elapsed:?}, read and summarised {total:?}: too slow"
    );
    result
}

/// One edit of a file.
#[derive(Clone, Debug)]
enum Mutation {
    /// Keep this fraction (per mille) of the bytes.
    Truncate(u16),
    /// Flip one bit of the byte at this position (modulo the length).
    FlipBit(usize, u8),
    /// Insert a byte.
    Insert(usize, u8),
    /// Delete up to this many bytes.
    Delete(usize, u8),
    /// Replace the n-th number token by garbage.
    ReplaceNumber(usize, String),
    /// Duplicate the n-th line.
    DuplicateLine(usize),
    /// Delete the n-th line.
    DeleteLine(usize),
    /// Swap two lines.
    SwapLines(usize, usize),
    /// Replace the n-th field of an IGES file by garbage, keeping the 80-column records:
    /// a number in the data columns of a G or P record, or an 8-column D field.
    ReplaceIgesField(usize, String),
}

/// Text that breaks numbers and counts: not numbers, out-of-range exponents, huge counts,
/// negative and fractional counts, zero (weights, denominators), far and tiny values.
fn garbage() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "",
            "-",
            "+",
            ".",
            "e",
            "x",
            "nan",
            "NaN",
            "inf",
            "-inf",
            "Infinity",
            "1e99999",
            "-1e99999",
            "1e-99999",
            "1D400",
            "1e10000",
            "1e+",
            "1/0",
            "0/0",
            "1/2/3",
            "--1",
            "0",
            "-0",
            "0.0",
            "-1",
            "-3",
            "1.5",
            "2.5",
            "3.",
            "1,2",
            "1 2",
            "0x10",
            "\u{0}",
            "\u{ff11}",
            "\u{e9}",
            "999999",
            "1000000",
            "1000001",
            "99999999",
            "100000000",
            "4294967297",
            "18446744073709551616",
            "99999999999999999999",
            "1e20",
            "-1e20",
            "1e-20",
            "1e300",
            "123456789012345678901234567890",
            "65",
            "64",
            "17",
            "16",
            "3",
            "2",
            "1",
            "\"",
            "{",
            "}",
            "[",
            "]",
            ";",
            "H",
            "5H",
            "99H",
            "1H,",
            ",",
            "\n",
        ])
        .prop_map(str::to_string),
        // Long runs of digits (above the exact parser's 2000-digit limit too).
        (1usize..3000).prop_map(|n| "9".repeat(n)),
        "[0-9eEdD.+/-]{1,12}",
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        1 => (0u16..1000).prop_map(Mutation::Truncate),
        2 => (any::<usize>(), 0u8..8).prop_map(|(p, b)| Mutation::FlipBit(p, b)),
        2 => (any::<usize>(), any::<u8>()).prop_map(|(p, b)| Mutation::Insert(p, b)),
        2 => (any::<usize>(), 1u8..64).prop_map(|(p, n)| Mutation::Delete(p, n)),
        4 => (any::<usize>(), garbage()).prop_map(|(k, g)| Mutation::ReplaceNumber(k, g)),
        2 => any::<usize>().prop_map(Mutation::DuplicateLine),
        1 => any::<usize>().prop_map(Mutation::DeleteLine),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        4 => (any::<usize>(), garbage()).prop_map(|(k, g)| Mutation::ReplaceIgesField(k, g)),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let len = bytes.len();
    match m {
        Mutation::Truncate(per_mille) => bytes.truncate(len * usize::from(*per_mille) / 1000),
        Mutation::FlipBit(p, bit) if len > 0 => bytes[p % len] ^= 1 << bit,
        Mutation::Insert(p, b) => bytes.insert(p % (len + 1), *b),
        Mutation::Delete(p, n) if len > 0 => {
            let start = p % len;
            let end = (start + usize::from(*n)).min(len);
            bytes.drain(start..end);
        }
        Mutation::ReplaceNumber(k, g) => {
            let spans = number_tokens(bytes);
            if !spans.is_empty() {
                let (a, b) = spans[k % spans.len()];
                bytes.splice(a..b, g.bytes());
            }
        }
        Mutation::DuplicateLine(k) => {
            let lines = line_spans(bytes);
            if !lines.is_empty() {
                let (a, b) = lines[k % lines.len()];
                let mut copy = bytes[a..b].to_vec();
                if copy.last() != Some(&b'\n') {
                    copy.insert(0, b'\n');
                }
                bytes.splice(b..b, copy);
            }
        }
        Mutation::DeleteLine(k) => {
            let lines = line_spans(bytes);
            if !lines.is_empty() {
                let (a, b) = lines[k % lines.len()];
                bytes.drain(a..b);
            }
        }
        Mutation::SwapLines(i, j) => {
            let lines = line_spans(bytes);
            if !lines.is_empty() {
                let (x, y) = (lines[i % lines.len()], lines[j % lines.len()]);
                let (first, second) = if x.0 <= y.0 { (x, y) } else { (y, x) };
                if first != second {
                    let mut out = bytes[..first.0].to_vec();
                    out.extend_from_slice(&bytes[second.0..second.1]);
                    out.extend_from_slice(&bytes[first.1..second.0]);
                    out.extend_from_slice(&bytes[first.0..first.1]);
                    out.extend_from_slice(&bytes[second.1..]);
                    *bytes = out;
                }
            }
        }
        Mutation::ReplaceIgesField(k, g) => {
            let fields = iges_fields(bytes);
            if !fields.is_empty() {
                let g = g.replace(['\n', '\r'], " ");
                replace_iges_field(bytes, fields[k % fields.len()], &g);
            }
        }
        _ => {}
    }
}

/// The format a mutated fixture is read as: mostly its own, sometimes detected, sometimes
/// another reader (a file with the wrong extension).
fn format_for(own: Format, pick: u8) -> Option<Format> {
    match pick % 8 {
        0..=4 => Some(own),
        5 | 6 => None,
        _ => FORMATS[usize::from(pick / 8) % FORMATS.len()],
    }
}

/// Text made of the pieces model files are made of, after a plausible header.
fn model_like_text() -> impl Strategy<Value = String> {
    let header = prop::sample::select(vec![
        "",
        "{\"patches\": [",
        "{\"patches\": [{\"kind\": \"nurbs\", \"degree\": [",
        "{\"patches\": [{\"kind\": \"bezier\", \"degree\": [1, 1], \"points\": [",
        "1\n3 3\n",
        "2\n1 1\n",
        "1\n1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n",
        "f 1 2 3\n",
        "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n",
    ]);
    let piece = prop::sample::select(vec![
        "0",
        "1",
        "2",
        "3",
        "16",
        "-1",
        "0.5",
        "1/3",
        "1e3",
        "nan",
        " ",
        " ",
        ", ",
        ",",
        "\n",
        "\n",
        "[",
        "]",
        "{",
        "}",
        "\"",
        ":",
        "\"kind\"",
        "\"nurbs\"",
        "\"bezier\"",
        "\"degree\"",
        "\"points\"",
        "\"weights\"",
        "\"knots_u\"",
        "\"knots_v\"",
        "null",
        "true",
        "v ",
        "f ",
        "vn ",
        "#",
        "/",
        "//",
        "x",
        "#1",
        "#2=",
        "(",
        ")",
        "'",
        ";",
        "$",
        "*",
        ".T.",
        "ADVANCED_FACE",
        "B_SPLINE_SURFACE_WITH_KNOTS",
        "CARTESIAN_POINT",
    ]);
    (header, prop::collection::vec(piece, 0..300))
        .prop_map(|(h, pieces)| format!("{h}{}", pieces.concat()))
}

proptest! {
    #![proptest_config(config())]

    /// Random bytes, forced to each reader and auto-detected.
    #[test]
    fn random_bytes_never_panic(
        bytes in prop::collection::vec(any::<u8>(), 0..2048),
        pick in 0usize..FORMATS.len(),
    ) {
        let _ = read_checked("random.bin", &bytes, FORMATS[pick]);
    }

    /// Random text made of model-file pieces (numbers, brackets, keywords, separators).
    #[test]
    fn model_like_text_never_panics(text in model_like_text(), pick in 0usize..FORMATS.len()) {
        let _ = read_checked("random.txt", text.as_bytes(), FORMATS[pick]);
    }

    /// Random IGES-like records: 80 columns with a section letter in column 73.
    #[test]
    fn random_iges_records_never_panic(
        records in prop::collection::vec(
            ("[ -~]{0,72}", prop::sample::select(vec!['S', 'G', 'D', 'P', 'T', 'X', ' '])),
            0..40,
        ),
        auto in any::<bool>(),
    ) {
        let text: String = records
            .iter()
            .enumerate()
            .map(|(i, (body, section))| format!("{body:<72}{section}{:>7}\n", i + 1))
            .collect();
        let format = if auto { None } else { Some(Format::Iges) };
        let _ = read_checked("random.igs", text.as_bytes(), format);
    }

    /// Real fixtures, edited: truncated, bits flipped, bytes inserted and deleted, numbers
    /// replaced by garbage, lines duplicated, deleted and swapped.
    #[test]
    fn mutated_fixtures_never_panic(
        which in any::<prop::sample::Index>(),
        mutations in prop::collection::vec(mutation(), 1..5),
        pick in any::<u8>(),
    ) {
        let f = which.get(fixtures());
        let mut bytes = f.bytes.clone();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        let _ = read_checked(f.name, &bytes, format_for(f.format, pick));
    }

    /// IGES fixtures with fields replaced by garbage, records kept 80 columns wide (so the
    /// reader gets past the record checks into the entities).
    #[test]
    fn iges_fields_replaced_never_panic(
        which in 0usize..4,
        edits in prop::collection::vec((any::<usize>(), garbage()), 1..4),
        auto in any::<bool>(),
    ) {
        let igs: Vec<&Fixture> = fixtures().iter().filter(|f| f.format == Format::Iges).collect();
        let f = igs[which % igs.len()];
        let mut bytes = f.bytes.clone();
        for (k, g) in edits {
            apply(&mut bytes, &Mutation::ReplaceIgesField(k, g));
        }
        let format = if auto { None } else { Some(Format::Iges) };
        let _ = read_checked(f.name, &bytes, format);
    }

    /// A number in a real fixture replaced by garbage: the error, if any, names a place.
    #[test]
    fn one_number_replaced_gives_a_placed_error(
        which in any::<prop::sample::Index>(),
        k in any::<usize>(),
        g in garbage(),
    ) {
        let f = which.get(fixtures());
        let mut bytes = f.bytes.clone();
        apply(&mut bytes, &Mutation::ReplaceNumber(k, g));
        if let Err(e) = read_checked(f.name, &bytes, Some(f.format)) {
            // Only an empty file or an unknown format is a whole-file error; a broken number
            // is somewhere.
            if e.place == Place::File {
                let m = &e.message;
                prop_assert!(
                    m.contains("empty")
                        || m.contains("no rational B-spline surface")
                        || m.contains("no directory entry")
                        || m.contains("no face"),
                    "a whole-file error for one bad number: {e}"
                );
            }
        }
    }
}

/// Declared counts far beyond the data, and NURBS surfaces whose Bézier split would be huge,
/// fail at once with a placed message (nothing is allocated by the declared or implied size).
#[test]
fn huge_declared_or_implied_sizes_fail_fast() {
    let zeros = vec!["0"; 100_000].join(",");
    // Few control points, but degree 64 with 31 x 31 knot spans: 31 * 31 * 65 * 65 Bézier
    // control points after the split.
    let knots: Vec<String> = (0..=(95 + 64)).map(|i| i.to_string()).collect();
    let knots = knots.join(",");
    let grid = vec!["[0,0,0]"; 95 * 95].join(",");
    // (name, content, format, what the message must say)
    let cases: [(&str, String, Format, &str); 6] = [
        (
            "count.bpt",
            "999999\n3 3\n0 0 0\n".to_string(),
            Format::Bpt,
            "count.bpt: line 3: the file ends where patch 0: point 1 was expected",
        ),
        (
            "count.bpt",
            format!("{}\n1 1\n", usize::MAX),
            Format::Bpt,
            "count.bpt: line 1: the patch count: 18446744073709551615 is more than the 1000000 allowed",
        ),
        (
            "count.teaset",
            "1\n1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16\n100000000\n0,0,0\n".to_string(),
            Format::Teaset,
            "count.teaset: line 4: the file ends where vertex 2 was expected",
        ),
        (
            "count.teaset",
            format!("1000000\n{}\n", "1,".repeat(15) + "1"),
            Format::Teaset,
            "count.teaset: line 2: the file ends where patch 1: vertex index 0 was expected",
        ),
        (
            "count.json",
            format!(
                "{{\"patches\": [{{\"kind\": \"nurbs\", \"degree\": [1, 1], \"knots_u\": [{zeros}], \"knots_v\": [{zeros}], \"points\": []}}]}}"
            ),
            Format::Json,
            "count.json: patch 0, points: the knot vectors give 99998 x 99998 = 9999600004 control points, found 0",
        ),
        (
            "split.json",
            format!(
                "{{\"patches\": [{{\"kind\": \"nurbs\", \"degree\": [64, 64], \"knots_u\": [{knots}], \"knots_v\": [{knots}], \"points\": [{grid}]}}]}}"
            ),
            Format::Json,
            "split.json: patch 0: the surface splits into 31 x 31 Bézier patches of degree (64,64)",
        ),
    ];
    for (name, text, format, expected) in cases {
        let start = Instant::now();
        let r = read_checked(name, text.as_bytes(), Some(format));
        let elapsed = start.elapsed();
        match r {
            Ok(_) => panic!(
                "{name}: read a model from {:?}",
                &text[..text.len().min(80)]
            ),
            Err(e) => assert!(
                e.to_string().starts_with(expected),
                "{name}: {e}\nexpected: {expected}"
            ),
        }
        assert!(elapsed < Duration::from_secs(2), "{name}: took {elapsed:?}");
    }
}

/// The fixtures read as they are, under their own format and auto-detected.
#[test]
fn unmutated_fixtures_read() {
    for f in fixtures() {
        read_checked(f.name, &f.bytes, Some(f.format)).expect("the fixture reads");
        let detected = read_checked(f.name, &f.bytes, None).expect("the fixture is detected");
        assert_eq!(detected.format, f.format, "{}", f.name);
    }
}

proptest! {
    #![proptest_config(config())]

    /// What `limn info` does with a model that reads: summarise it with the default welding
    /// (for IGES, a tolerance). Far coordinates overflow the welding grid of
    /// `src/model/topology.rs`; see `far_points_and_tiny_welds_do_not_panic` in
    /// tests/bad_input.rs.
    #[test]
    fn mutated_fixtures_summarise_with_the_default_weld(
        which in any::<prop::sample::Index>(),
        k in any::<usize>(),
        g in garbage(),
    ) {
        let f = which.get(fixtures());
        let mut bytes = f.bytes.clone();
        let m = if f.format == Format::Iges {
            Mutation::ReplaceIgesField(k, g)
        } else {
            Mutation::ReplaceNumber(k, g)
        };
        apply(&mut bytes, &m);
        if let Ok(m) = read_checked(f.name, &bytes, Some(f.format)) {
            let _ = ModelInfo::of(f.name, &m, limn::model::default_weld(&m));
        }
    }
}
