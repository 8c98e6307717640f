//! `limn curves --kind parabolic`: the JSON contract on the teapot, SVG output, bad arguments
//! (exit 2, one line), no overwrite without --force.

use serde_json::Value;
use std::path::PathBuf;

use crate::common;
use common::limn;

fn tmp(name: &str) -> PathBuf {
    common::tmp("cli_curves", name)
}

const TEAPOT: &str = "fixtures/bezier/teapot.bpt";

#[test]
fn parabolic_json_contract() {
    let (code, out, err) = limn(&[
        "curves",
        TEAPOT,
        "--kind",
        "parabolic",
        "--format",
        "json",
        "--tol",
        "1e-4",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let r: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(r["kind"], "parabolic");
    assert!(r.get("view").is_none());
    assert_eq!(r["certified"], true);
    assert_eq!(r["topology_certified"], true);
    let curves = r["curves"].as_array().unwrap();
    assert!(!curves.is_empty());
    for c in curves {
        assert_eq!(
            c["points"].as_array().unwrap().len(),
            c["points_uv"].as_array().unwrap().len()
        );
    }
    assert!(!r["ending_edges"].as_array().unwrap().is_empty());
    assert!(r["degenerate"]
        .as_array()
        .unwrap()
        .iter()
        .any(|d| d["kind"] == "parabolic line"));
}

#[test]
fn svg_output_and_no_overwrite() {
    let path = tmp("teapot-parabolic.svg");
    let _ = std::fs::remove_file(&path);
    let p = path.to_str().unwrap();
    let args = [
        "curves",
        TEAPOT,
        "--kind",
        "parabolic",
        "--format",
        "svg",
        "-o",
        p,
    ];
    let (code, _, err) = limn(&args);
    assert_eq!(code, Some(0), "{err}");
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"));
    assert!(svg.contains("parabolic curves"));
    let (code, _, err) = limn(&args);
    assert_eq!(code, Some(2));
    assert!(err.contains("not overwritten"), "{err}");
    assert_eq!(std::fs::read_to_string(&path).unwrap(), svg);
}

#[test]
fn bad_arguments_are_exit_2_with_one_line() {
    for args in [
        &["curves", TEAPOT, "--kind", "bitangents"][..],
        &["curves", TEAPOT][..],
        &["curves", TEAPOT, "--kind", "flecnodal", "--tol", "0"][..],
        &["curves", TEAPOT, "--kind", "parabolic", "--tol", "-1"][..],
        &["curves", TEAPOT, "--kind", "parabolic", "--dir", "0,0,0"][..],
        &["curves", TEAPOT, "--kind", "parabolic", "--threads", "0"][..],
        &["curves", "no/such/file.bpt", "--kind", "parabolic"][..],
    ] {
        let (code, out, err) = limn(args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(out.is_empty());
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    }
}

/// `--time-limit`: a run that reaches it stops subdividing and reports what is left as
/// unresolved, naming the limit; nothing is claimed certified. A bad value is exit 2.
#[test]
fn a_time_limit_leaves_the_rest_unresolved() {
    for cmd in [
        &["curves", TEAPOT, "--kind", "parabolic"][..],
        &["silhouette", TEAPOT, "--dir", "1,2,3", "--tol", "1e-3"][..],
    ] {
        let mut args = cmd.to_vec();
        args.extend(["--time-limit", "0", "--format", "json"]);
        let r = common::time_limited(&args);
        assert_eq!(r["topology_certified"], false);
    }
    let (code, _, err) = limn(&[
        "curves",
        TEAPOT,
        "--kind",
        "parabolic",
        "--time-limit",
        "-1",
    ]);
    assert_eq!(code, Some(2));
    assert!(err.contains("--time-limit"), "{err}");
}

/// A polygon mesh is not silently reported as having no curves: both curve commands refuse it
/// (exit 2, one line naming the file and why).
#[test]
fn a_mesh_is_refused_not_answered_with_no_curves() {
    let mesh = "fixtures/meshes/keenan/blub/blub_control_mesh.obj";
    for args in [
        &["curves", mesh, "--kind", "parabolic"][..],
        &["silhouette", mesh, "--dir", "1,2,3"][..],
    ] {
        let (code, out, err) = limn(args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(out.is_empty());
        assert_eq!(err.trim_end().lines().count(), 1);
        assert!(err.contains(mesh) && err.contains("mesh"), "{err}");
    }
}

/// Every patch fixture: `limn curves --kind parabolic` ends without panic (a time limit keeps
/// the large IGES models short) and writes well-formed JSON.
#[test]
fn parabolic_curves_of_every_patch_fixture() {
    let mut files = vec![
        "fixtures/bezier/newell_teaset/teacup".to_string(),
        "fixtures/bezier/newell_teaset/teaspoon".to_string(),
    ];
    for dir in ["fixtures/iges/occt", "fixtures/iges/forIGES"] {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
        for e in std::fs::read_dir(root).unwrap() {
            let p = e.unwrap().path();
            if matches!(p.extension().and_then(|x| x.to_str()), Some("igs" | "iges")) {
                files.push(format!(
                    "{dir}/{}",
                    p.file_name().unwrap().to_str().unwrap()
                ));
            }
        }
    }
    assert!(files.len() >= 10);
    for f in &files {
        let (code, out, err) = limn(&[
            "curves",
            f,
            "--kind",
            "parabolic",
            "--time-limit",
            "1",
            "--format",
            "json",
        ]);
        assert_eq!(code, Some(0), "{f}: {err}");
        let r: Value = serde_json::from_str(&out).unwrap_or_else(|e| panic!("{f}: {e}"));
        assert_eq!(r["kind"], "parabolic", "{f}");
    }
}

/// A graph patch `z = Σ c xⁱ yʲ` over a rectangle as a JSON model (exact coordinates).
fn graph_model(
    name: &str,
    terms: &[(usize, usize, (i64, i64))],
    x: [(i64, i64); 2],
    y: [(i64, i64); 2],
) -> PathBuf {
    let q = |(n, d): (i64, i64)| limn::number::Rational::from((n, d));
    let terms: Vec<_> = terms.iter().map(|&(i, j, c)| (i, j, q(c))).collect();
    let p = limn::testing::shapes::graph(&terms, x.map(q), y.map(q));
    let pts: Vec<String> = p
        .points()
        .iter()
        .map(|c| format!("[\"{}\",\"{}\",\"{}\"]", c[0], c[1], c[2]))
        .collect();
    let [m, n] = p.degree();
    let text = format!(
        r#"{{"patches":[{{"kind":"bezier","degree":[{m},{n}],"points":[{}]}}]}}"#,
        pts.join(",")
    );
    let path = tmp(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The graph z = xy + (x³ + y³)/6 over [0, 5/2] × [0, 3]: its only flecnodal curve is the
/// segment x + y = 2.
fn cubic_graph_model() -> PathBuf {
    graph_model(
        "cubic_graph.json",
        &[(1, 1, (1, 1)), (3, 0, (1, 6)), (0, 3, (1, 6))],
        [(0, 1), (5, 2)],
        [(0, 1), (3, 1)],
    )
}

#[test]
fn flecnodal_json_contract_and_formats() {
    let model = cubic_graph_model();
    let m = model.to_str().unwrap();
    let (code, out, err) = limn(&[
        "curves",
        m,
        "--kind",
        "flecnodal",
        "--format",
        "json",
        "--tol",
        "1e-3",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let r: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(r["kind"], "flecnodal");
    assert_eq!(r["certified"], true, "{out}");
    assert!(r["error_bound"].as_f64().unwrap() <= r["tolerance"].as_f64().unwrap());
    let curves = r["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 1);
    let c = &curves[0];
    assert_eq!(c["complete"], true);
    let n = c["points"].as_array().unwrap().len();
    for field in ["points_uv", "directions_uv", "lines"] {
        assert_eq!(c[field].as_array().unwrap().len(), n, "{field}");
    }
    for p in c["points"].as_array().unwrap() {
        let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        assert!((x + y - 2.0).abs() < 1e-9);
    }
    assert!(r["unresolved"].as_array().unwrap().is_empty());
    assert!(r["degenerate"].as_array().unwrap().is_empty());
    assert_eq!(r["stats"]["curves"], 1);
    // Text, SVG and OBJ.
    let (code, out, _) = limn(&["curves", m, "--kind", "flecnodal"]);
    assert_eq!(code, Some(0));
    assert!(
        out.contains("1 flecnodal curves") && out.contains("certified"),
        "{out}"
    );
    let (code, out, _) = limn(&["curves", m, "--kind", "flecnodal", "--format", "svg"]);
    assert_eq!(code, Some(0));
    assert!(out.starts_with("<svg") || out.starts_with("<?xml"));
    let (code, out, _) = limn(&["curves", m, "--kind", "flecnodal", "--format", "obj"]);
    assert_eq!(code, Some(0));
    assert!(out.lines().any(|l| l.starts_with("l ")));
}

#[test]
fn flecnodal_with_a_time_limit_is_not_certified() {
    common::time_limited(&[
        "curves",
        TEAPOT,
        "--kind",
        "flecnodal",
        "--time-limit",
        "0",
        "--format",
        "json",
    ]);
}

#[test]
fn flecnodal_of_a_plane_is_degenerate() {
    let path = tmp("plane.json");
    std::fs::write(
        &path,
        r#"{"patches":[{"kind":"bezier","degree":[1,1],"points":[[0,0,0],[0,1,0],[1,0,0],[1,1,0]]}]}"#,
    )
    .unwrap();
    let (code, out, err) = limn(&[
        "curves",
        path.to_str().unwrap(),
        "--kind",
        "flecnodal",
        "--format",
        "json",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let r: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(r["certified"], false);
    assert_eq!(r["degenerate"].as_array().unwrap().len(), 1);
    assert!(r["curves"].as_array().unwrap().is_empty());
}

/// The double well z = (x² − 1)² + y² + xy/2 over [−3/2, 3/2] × [−1, 1]: one family of
/// bitangent planes, touching at x = ∓√(33/32) (tests/bitangent_curves.rs).
#[test]
fn bitangent_json_contract_and_formats() {
    let model = graph_model(
        "double_well.json",
        &[
            (4, 0, (1, 1)),
            (2, 0, (-2, 1)),
            (0, 0, (1, 1)),
            (0, 2, (1, 1)),
            (1, 1, (1, 2)),
        ],
        [(-3, 2), (3, 2)],
        [(-1, 1), (1, 1)],
    );
    let m = model.to_str().unwrap();
    let (code, out, err) = limn(&[
        "curves",
        m,
        "--kind",
        "bitangent",
        "--format",
        "json",
        "--tol",
        "1e-2",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let r: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(r["kind"], "bitangent");
    assert_eq!(r["certified"], true, "{out}");
    assert!(r["error_bound"].as_f64().unwrap() <= r["tolerance"].as_f64().unwrap());
    let curves = r["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 1, "each pair once");
    let c = &curves[0];
    assert_eq!(c["complete"], true);
    assert_eq!(c["patches"], serde_json::json!([0, 0]));
    let n = c["points"].as_array().unwrap().len();
    for field in [
        "points_second",
        "points_uv",
        "points_uv_second",
        "lines",
        "normals",
    ] {
        assert_eq!(c[field].as_array().unwrap().len(), n, "{field}");
    }
    let x0 = (33.0f64 / 32.0).sqrt();
    for (p, q) in c["points"]
        .as_array()
        .unwrap()
        .iter()
        .zip(c["points_second"].as_array().unwrap())
    {
        let (a, b) = (p[0].as_f64().unwrap(), q[0].as_f64().unwrap());
        assert!(
            (a.abs() - x0).abs() < 1e-6 && (a + b).abs() < 1e-6,
            "{p} {q}"
        );
    }
    assert!(r["unresolved"].as_array().unwrap().is_empty());
    assert_eq!(r["stats"]["pairs"], 1);
    assert_eq!(r["stats"]["pairs_solved"], 1);
    // Text, SVG and OBJ.
    let (code, out, _) = limn(&["curves", m, "--kind", "bitangent"]);
    assert_eq!(code, Some(0));
    assert!(
        out.contains("1 bitangent curves") && out.contains("certified"),
        "{out}"
    );
    let (code, out, _) = limn(&["curves", m, "--kind", "bitangent", "--format", "svg"]);
    assert_eq!(code, Some(0));
    assert!(out.starts_with("<svg") || out.starts_with("<?xml"));
    let (code, out, _) = limn(&["curves", m, "--kind", "bitangent", "--format", "obj"]);
    assert_eq!(code, Some(0));
    assert_eq!(out.lines().filter(|l| l.starts_with("l ")).count(), 2);
}

#[test]
fn bitangent_with_a_time_limit_is_not_certified() {
    common::time_limited(&[
        "curves",
        TEAPOT,
        "--kind",
        "bitangent",
        "--time-limit",
        "0",
        "--format",
        "json",
    ]);
}

#[test]
fn events_json_svg_and_bad_kinds() {
    let (code, out, err) = limn(&["events", TEAPOT, "--kinds", "parabolic", "--format", "json"]);
    assert_eq!(code, Some(0), "{err}");
    let r: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(r["sources_certified"], true);
    assert_eq!(r["families"][0]["kind"], "parabolic");
    let curves = r["curves"].as_array().unwrap();
    assert!(!curves.is_empty());
    for c in curves {
        assert_eq!(c["kind"], "parabolic");
        for d in c["directions"].as_array().unwrap() {
            let v: Vec<f64> = d
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            assert!(((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() - 1.0).abs() < 1e-9);
        }
    }
    // With a tolerance the pieces are small enough for every curve's error on the sphere to be
    // bounded: certified.
    let (code, out, err) = limn(&[
        "events",
        TEAPOT,
        "--kinds",
        "parabolic",
        "--format",
        "json",
        "--tol",
        "1e-4",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let r: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(r["certified"], true);
    let largest = r["largest_error"].as_f64().unwrap();
    assert!(largest > 0.0 && largest < 0.5, "{largest}");
    for c in r["curves"].as_array().unwrap() {
        assert_eq!(c["certified"], true);
        assert!(c["error"].as_f64().unwrap() <= largest);
    }
    assert_eq!(r["families"][0]["unbounded"], 0);
    let (code, out, _) = limn(&["events", TEAPOT, "--kinds", "parabolic", "--format", "svg"]);
    assert_eq!(code, Some(0));
    assert!(out.starts_with("<svg") || out.starts_with("<?xml"));
    for args in [
        &["events", TEAPOT, "--kinds", "parabolic,cusps"][..],
        &["events", TEAPOT, "--format", "obj"][..],
        &["events", "no/such/file.bpt"][..],
    ] {
        let (code, out, err) = limn(args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(out.is_empty());
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    }
}
