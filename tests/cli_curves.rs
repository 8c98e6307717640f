//! `limn curves --kind parabolic`: the JSON contract on the teapot, SVG output, bad arguments
//! (exit 2, one line), no overwrite without --force.

use serde_json::Value;
use std::path::PathBuf;

mod common;
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
        &["curves", TEAPOT, "--kind", "flecnodal"][..],
        &["curves", TEAPOT][..],
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
        let (code, out, err) = limn(&args);
        assert_eq!(code, Some(0), "{err}");
        let r: Value = serde_json::from_str(&out).unwrap();
        assert_eq!(r["topology_certified"], false);
        assert_eq!(r["certified"], false);
        let unresolved = r["unresolved"].as_array().unwrap();
        assert!(!unresolved.is_empty());
        assert!(unresolved
            .iter()
            .all(|u| u["reason"].as_str().unwrap().contains("time limit")));
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
