//! `limn silhouette`: the JSON contract on an exact model, output files, bad arguments.

use limn::number::Rational;
use limn::testing::shapes;
use serde_json::Value;
use std::path::PathBuf;

use crate::common;
use common::limn;

fn tmp(name: &str) -> PathBuf {
    common::tmp("cli_silhouette", name)
}

/// The exact sphere of radius 2 as a native JSON model, numbers written as exact fractions.
fn sphere_json() -> PathBuf {
    let path = tmp("sphere.json");
    std::fs::write(
        &path,
        limn::io::write_model(&shapes::sphere(&Rational::from(2))),
    )
    .unwrap();
    path
}

#[test]
fn sphere_silhouette_json_contract() {
    let model = sphere_json();
    let (code, out, err) = limn(&[
        "silhouette",
        model.to_str().unwrap(),
        "--dir",
        "1,-2,3",
        "--format",
        "json",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        v["certified"], false,
        "without --tol the accuracy is not certified, and it says so"
    );
    assert_eq!(v["topology_certified"], true);
    let curves = v["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 1);
    let c = &curves[0];
    assert_eq!(c["closed"], true);
    assert_eq!(c["certified_topology"], true);
    // Every drawn point lies on the sphere's silhouette x - 2y + 3z = 0 (to drawing accuracy).
    for p in c["points"].as_array().unwrap() {
        let p: Vec<f64> = p
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!((p[0] - 2.0 * p[1] + 3.0 * p[2]).abs() < 1e-6, "{p:?}");
        assert!(((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 2.0).abs() < 1e-9);
    }
    assert_eq!(
        c["points"].as_array().unwrap().len(),
        c["points_uv"].as_array().unwrap().len()
    );
    for key in [
        "unresolved",
        "unjoined_edges",
        "degenerate",
        "stats",
        "view",
        "model",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(
        v["stats"]["escalations"]["exact"].as_u64().unwrap()
            + v["stats"]["escalations"]["undecided"].as_u64().unwrap(),
        v["stats"]["escalations"]["exact"].as_u64().unwrap()
    );
}

#[test]
fn output_files_are_not_overwritten_without_force() {
    let out = tmp("teapot.svg");
    let _ = std::fs::remove_file(&out);
    let o = out.to_str().unwrap();
    let (code, _, err) = limn(&[
        "silhouette",
        "fixtures/bezier/teapot.bpt",
        "--dir",
        "1,2,3",
        "--format",
        "svg",
        "-o",
        o,
    ]);
    assert_eq!(code, Some(0), "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("topology certified"));
    std::fs::write(&out, "mine").unwrap();
    let (code, _, err) = limn(&[
        "silhouette",
        "fixtures/bezier/teapot.bpt",
        "--dir",
        "1,2,3",
        "--format",
        "svg",
        "-o",
        o,
    ]);
    assert_eq!(code, Some(2));
    assert!(err.contains("not overwritten"), "{err}");
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        "mine",
        "the user's file is untouched"
    );
    let (code, _, _) = limn(&[
        "silhouette",
        "fixtures/bezier/teapot.bpt",
        "--dir",
        "1,2,3",
        "--format",
        "svg",
        "-o",
        o,
        "--force",
    ]);
    assert_eq!(code, Some(0));
    assert!(std::fs::read_to_string(&out).unwrap().starts_with("<svg"));
}

#[test]
fn bad_view_arguments_are_one_line_exit_2() {
    for (args, needle) in [
        (
            &["silhouette", "fixtures/bezier/teapot.bpt", "--dir", "0,0,0"][..],
            "zero vector",
        ),
        (
            &["silhouette", "fixtures/bezier/teapot.bpt", "--dir", "1,2"],
            "three numbers",
        ),
        (
            &["silhouette", "fixtures/bezier/teapot.bpt", "--dir", "1,x,2"],
            "not a number",
        ),
        (&["silhouette", "fixtures/bezier/teapot.bpt"], "--dir"),
        (
            &[
                "silhouette",
                "fixtures/bezier/teapot.bpt",
                "--dir",
                "1,2,3",
                "--eye",
                "0,0,9",
            ],
            "cannot be used with",
        ),
        (
            &[
                "silhouette",
                "fixtures/bezier/teapot.bpt",
                "--dir",
                "1,2,3",
                "--max-depth",
                "99",
            ],
            "--max-depth",
        ),
        (
            &[
                "silhouette",
                "fixtures/bezier/teapot.bpt",
                "--dir",
                "1,2,3",
                "--threads",
                "0",
            ],
            "--threads",
        ),
        (
            &["silhouette", "no/such/file.bpt", "--dir", "1,2,3"],
            "no/such/file.bpt",
        ),
    ] {
        let (code, out, err) = limn(args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(out.is_empty());
    }
}

#[test]
fn perspective_text_summary() {
    let model = sphere_json();
    let (code, out, err) = limn(&[
        "silhouette",
        model.to_str().unwrap(),
        "--eye",
        "1,2,9",
        "--threads",
        "1",
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert!(
        out.contains("curves: 1 (1 closed); topology certified"),
        "{out}"
    );
    assert!(out.contains("8 x collapsed side"), "{out}");
}

#[test]
fn float_baselines_are_marked_uncertified() {
    for method in ["mesh", "srf-node"] {
        let (code, out, err) = limn(&[
            "silhouette",
            "fixtures/bezier/teapot.bpt",
            "--dir",
            "1,2,3",
            "--method",
            method,
            "--format",
            "json",
        ]);
        assert_eq!(code, Some(0), "{err}");
        let v: Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["method"], method);
        assert_eq!(v["certified"], false);
        assert_eq!(v["topology_certified"], false);
        assert!(v["curves"]
            .as_array()
            .unwrap()
            .iter()
            .all(|c| c["certified_topology"] == false));
    }
}

#[test]
fn tolerance_certifies_the_drawing() {
    let model = sphere_json();
    let (code, out, err) = limn(&[
        "silhouette",
        model.to_str().unwrap(),
        "--dir",
        "1,-2,3",
        "--tol",
        "1e-4",
        "--format",
        "json",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["certified"], true);
    let tol = v["tolerance"].as_f64().unwrap();
    // Relative to the bounding-box diagonal of the control points (a cube of side 4 about the origin).
    assert!((tol - 1e-4 * (48f64).sqrt()).abs() < 1e-12, "{tol}");
    let bound = v["curves"][0]["error_bound"].as_f64().unwrap();
    assert!(bound <= tol);
    let (code, _, err) = limn(&[
        "silhouette",
        model.to_str().unwrap(),
        "--dir",
        "1,2,3",
        "--tol",
        "-1",
    ]);
    assert_eq!(code, Some(2));
    assert!(err.contains("--tol"), "{err}");
}

#[test]
fn certificates_are_written_and_checked_independently() {
    let model = "fixtures/bezier/teapot.bpt";
    let cert = tmp("teapot-cert.json");
    let _ = std::fs::remove_file(&cert);
    let c = cert.to_str().unwrap();
    let (code, _, err) = limn(&["silhouette", model, "--dir", "1,2,3", "--certificate", c]);
    assert_eq!(code, Some(0), "{err}");
    // Not overwritten without --force.
    let (code, _, err) = limn(&["silhouette", model, "--dir", "1,2,3", "--certificate", c]);
    assert_eq!(code, Some(2));
    assert!(err.contains("exists"), "{err}");
    let (code, out, err) = limn(&["check", model, c]);
    assert_eq!(code, Some(0), "{out}{err}");
    assert!(out.starts_with("valid: 32 patches"), "{out}");
    assert!(out.contains("the whole model is decided"), "{out}");
    // JSON verdict.
    let (code, out, _) = limn(&["check", model, c, "--format", "json"]);
    assert_eq!(code, Some(0));
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["valid"], true);
    assert_eq!(v["summary"]["patches"], 32);

    // The certificate read back and mutated: a sign flipped, a box moved, a piece dropped,
    // a different view, another model: each is invalid (exit 1) with the failing item named.
    let text = std::fs::read_to_string(&cert).unwrap();
    let original: Value = serde_json::from_str(&text).unwrap();
    let first_with = |key: &str| {
        original["patches"]
            .as_array()
            .unwrap()
            .iter()
            .position(|p| !p["curve"][key].as_array().unwrap().is_empty())
            .unwrap()
    };
    let pa = first_with("arcs");
    type Mutation = Box<dyn Fn(&mut Value)>;
    // Drops the last entry of a patch's list.
    let pop = |patch: usize, list: &'static str| -> Mutation {
        Box::new(move |v: &mut Value| {
            v["patches"][patch]["curve"][list]
                .as_array_mut()
                .unwrap()
                .pop();
        })
    };
    let mutations: Vec<(&str, Mutation)> = vec![
        (
            "cell",
            Box::new(move |v: &mut Value| {
                let s = &mut v["patches"][pa]["curve"]["cells"][0]["sign"];
                *s = Value::from(-s.as_i64().unwrap());
            }),
        ),
        ("cells", pop(pa, "cells")),
        ("arc", pop(pa, "arcs")),
        (
            "patch",
            Box::new(|v: &mut Value| v["view"]["vector"][0] = Value::from("2")),
        ),
    ];
    for (what, mutate) in mutations {
        let mut v = original.clone();
        mutate(&mut v);
        let bad = tmp(&format!("teapot-cert-{what}.json"));
        std::fs::write(&bad, v.to_string()).unwrap();
        let (code, out, err) = limn(&["check", model, bad.to_str().unwrap()]);
        assert_eq!(code, Some(1), "{what}: {out}{err}");
        assert!(out.starts_with("invalid: "), "{what}: {out}");
        assert!(out.contains(what), "{what}: {out}");
    }
    // Another model: the patch count differs.
    let (code, out, _) = limn(&["check", "fixtures/bezier/newell_teaset/teacup", c]);
    assert_eq!(code, Some(1), "{out}");
    // Not a certificate: exit 2, file and place named.
    let junk = tmp("junk-cert.json");
    std::fs::write(&junk, "{\"format\": 3}").unwrap();
    let (code, _, err) = limn(&["check", model, junk.to_str().unwrap()]);
    assert_eq!(code, Some(2));
    assert!(err.contains("junk-cert.json: line 1"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
}

#[test]
fn obj_output_has_one_polyline_per_curve() {
    let model = sphere_json();
    let m = model.to_str().unwrap();
    let (code, json, _) = limn(&[
        "silhouette",
        m,
        "--dir",
        "1,2,2",
        "--tol",
        "1e-4",
        "--format",
        "json",
    ]);
    assert_eq!(code, Some(0));
    let v: Value = serde_json::from_str(&json).unwrap();
    let points = v["curves"][0]["points"].as_array().unwrap().len();
    let (code, obj, err) = limn(&[
        "silhouette",
        m,
        "--dir",
        "1,2,2",
        "--tol",
        "1e-4",
        "--format",
        "obj",
    ]);
    assert_eq!(code, Some(0), "{err}");
    let verts = obj.lines().filter(|l| l.starts_with("v ")).count();
    let lines: Vec<&str> = obj.lines().filter(|l| l.starts_with("l ")).collect();
    assert_eq!(verts, points);
    assert_eq!(lines.len(), 1);
    // Closed: the polyline returns to its first vertex.
    let idx: Vec<usize> = lines[0][2..]
        .split(' ')
        .map(|s| s.parse().unwrap())
        .collect();
    assert_eq!(idx.len(), points + 1);
    assert_eq!(idx[0], idx[points]);
    assert!(obj.contains("# curve 0: closed, certified"), "{obj}");
}
