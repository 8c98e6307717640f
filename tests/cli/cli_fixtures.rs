//! `limn info` on every fixture, with the counts asserted, and `limn demo`.

use serde_json::Value;
use std::process::Command;

fn info(path: &str, extra: &[&str]) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_limn"))
        .args(["info", path, "--format", "json"])
        .args(extra)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run limn");
    assert!(
        out.status.success(),
        "{path}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON output")
}

fn topo(v: &Value, key: &str) -> i64 {
    v["topology"][key]
        .as_i64()
        .unwrap_or_else(|| panic!("topology.{key} in {v}"))
}

#[test]
fn newell_teapot_in_both_formats() {
    for path in [
        "fixtures/bezier/teapot.bpt",
        "fixtures/bezier/newell_teaset/teapot",
    ] {
        let v = info(path, &[]);
        assert_eq!(v["patches"], 32, "{path}");
        assert_eq!(v["degrees"]["3x3"], 32);
        assert_eq!(v["rational_patches"], 0);
        // Lid knob and bottom centre: 4 + 4 patch sides collapse to a point.
        assert_eq!(topo(&v, "collapsed_edges"), 8);
        // Body, lid, spout and handle are separate pieces: not a closed solid.
        assert_eq!(topo(&v, "components"), 4);
        assert_eq!(v["topology"]["closed"], false);
        assert_eq!(
            topo(&v, "shared_edges") + topo(&v, "boundary_edges"),
            topo(&v, "edges")
        );
        assert_eq!(
            v["bounding_box"]["min"],
            serde_json::json!([-3.0, -2.0, 0.0])
        );
    }
}

#[test]
fn teacup_and_teaspoon() {
    let cup = info("fixtures/bezier/newell_teaset/teacup", &[]);
    assert_eq!(cup["patches"], 26);
    assert_eq!(cup["format"], "teaset");
    let spoon = info("fixtures/bezier/newell_teaset/teaspoon", &[]);
    assert_eq!(spoon["patches"], 16);
    assert_eq!(topo(&spoon, "components"), 1);
}

#[test]
fn iges_torus_is_closed_with_genus_one_once_welded() {
    let v = info("fixtures/iges/occt/OCC26138_Torus.igs", &[]);
    assert_eq!(v["surfaces"], 1);
    assert_eq!(v["degrees"]["12x12"], 1);
    assert_eq!(v["topology"]["closed"], true);
    assert_eq!(topo(&v, "euler_characteristic"), 0);
    assert_eq!(topo(&v, "genus"), 1);
    assert_eq!(v["topology"]["weld"]["mode"], "absolute");
    // The trim of the underlying surface (across the seam of the closed torus, which limn
    // does not read yet) is reported, not silently dropped.
    let w = v["warnings"].as_array().unwrap();
    assert!(w.iter().any(|w| {
        let m = w["message"].as_str().unwrap();
        m.contains("used untrimmed") && m.contains("closed surface")
    }));
    assert!(v["faces"].is_null());
    // The file repeats its seam control points digit for digit: exact matching closes it too,
    // and nothing needed welding.
    assert_eq!(v["topology"]["max_weld_gap"], 0.0);
    let exact = info(
        "fixtures/iges/occt/OCC26138_Torus.igs",
        &["--weld", "exact"],
    );
    assert_eq!(exact["topology"]["weld"]["mode"], "exact");
    assert_eq!(topo(&exact, "genus"), 1);
}

#[test]
fn every_iges_fixture_loads() {
    let expect = [
        ("forIGES/128-000.igs", 1, 3),
        ("forIGES/surf128.igs", 4, 114),
        ("occt/BUC50025.igs", 7, 7),
        ("occt/CTS17806-38038.igs", 1, 5),
        ("occt/OCC17026-1.igs", 4, 80),
        ("occt/OCC26138_Torus.igs", 1, 1),
        ("occt/OCC8842_cone_Ideas.igs", 2, 5),
        ("occt/OCC8842_cylinder_Ideas.igs", 3, 6),
        ("occt/bug22869_Spring.igs", 2, 1062),
        ("occt/bug24012_face.igs", 1, 36),
        ("occt/occ22470.igs", 18, 68),
    ];
    for (file, surfaces, patches) in expect {
        let v = info(&format!("fixtures/iges/{file}"), &[]);
        assert_eq!(v["format"], "iges");
        assert_eq!(v["surfaces"], surfaces, "{file}");
        assert_eq!(v["patches"], patches, "{file}");
    }
    // The spring's faces on planes (entity 190) are reported as skipped.
    let spring = info("fixtures/iges/occt/bug22869_Spring.igs", &[]);
    let msgs: Vec<&str> = spring["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["message"].as_str().unwrap())
        .collect();
    assert!(msgs.iter().any(|m| m.contains("type 190")), "{msgs:?}");
}

#[test]
fn meshes_euler_characteristic_and_genus() {
    for (file, genus, faces) in [
        ("bob/bob_tri.obj", 1, 10688),
        ("spot/spot_triangulated.obj", 0, 5856),
        ("spot/spot_control_mesh.obj", 0, 180),
        ("blub/blub_triangulated.obj", 0, 14208),
        ("blub/blub_control_mesh.obj", 0, 112),
    ] {
        let v = info(&format!("fixtures/meshes/keenan/{file}"), &[]);
        let m = &v["meshes"][0];
        assert_eq!(m["faces"], faces, "{file}");
        assert_eq!(m["closed"], true, "{file}");
        assert_eq!(m["genus"], genus, "{file}");
        assert_eq!(m["euler_characteristic"], 2 - 2 * genus);
        assert!(v["topology"].is_null());
    }
}

#[test]
fn demo_runs_on_the_embedded_teapot() {
    // The main job: the teapot's silhouette from the default direction, topology certified.
    let out = Command::new(env!("CARGO_BIN_EXE_limn"))
        .args(["demo", "--format", "json"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["topology_certified"], true);
    assert_eq!(
        v["certified"], true,
        "the demo traces to 1e-3 of the diagonal"
    );
    assert_eq!(v["curves"].as_array().unwrap().len(), 10);
    let text = Command::new(env!("CARGO_BIN_EXE_limn"))
        .arg("demo")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("Bézier patches: 32"), "{text}");
    assert!(text.contains("topology certified"), "{text}");
    let svg = Command::new(env!("CARGO_BIN_EXE_limn"))
        .args(["demo", "--format", "svg"])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&svg.stdout).starts_with("<svg"));
}

#[test]
fn json_model_with_a_nurbs_surface() {
    let dir = std::env::temp_dir().join(format!("limn-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("model.json");
    // A bilinear NURBS with an interior knot in u (two Bézier pieces sharing an edge) and a
    // rational weight given as a string.
    std::fs::write(
        &path,
        r#"{"patches":[{"kind":"nurbs","degree":[1,1],"knots_u":[0,0,"1/2",1,1],"knots_v":[0,0,1,1],
           "points":[[0,0,0],[0,1,0],[1,0,0],[1,1,0.5],[2,0,0],[2,1,0]],"weights":[1,1,"3/2",1,1,1]}]}"#,
    )
    .unwrap();
    let v = info(path.to_str().unwrap(), &[]);
    assert_eq!(v["surfaces"], 1);
    assert_eq!(v["patches"], 2);
    assert_eq!(v["rational_patches"], 2);
    assert_eq!(topo(&v, "shared_edges"), 1);
    assert_eq!(topo(&v, "boundary_edges"), 6);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn obj_negative_indices_count_from_the_vertices_so_far() {
    let path = std::env::temp_dir().join(format!("limn-obj-{}.obj", std::process::id()));
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf -3 -2 -1\n",
    )
    .unwrap();
    let v = info(path.to_str().unwrap(), &[]);
    let m = &v["meshes"][0];
    assert_eq!(m["vertices"], 6);
    assert_eq!(m["components"], 2);
    assert_eq!(m["closed"], false);
    std::fs::remove_file(&path).ok();
}

#[test]
fn welding_never_merges_points_beyond_the_f64_range() {
    let path = std::env::temp_dir().join(format!("limn-far-{}.json", std::process::id()));
    let sq = |z: &str| {
        format!(
            r#"{{"kind":"bezier","degree":[1,1],"points":[[0,0,"{z}"],[0,1,"{z}"],[1,0,"{z}"],[1,1,"{z}"]]}}"#
        )
    };
    std::fs::write(
        &path,
        format!(r#"{{"patches":[{},{}]}}"#, sq("1e400"), sq("2e400")),
    )
    .unwrap();
    let v = info(path.to_str().unwrap(), &["--weld", "1e-6"]);
    assert_eq!(v["topology"]["shared_edges"], 0);
    assert_eq!(v["topology"]["closed"], false);
    std::fs::remove_file(&path).ok();
}

/// occ22470's B-rep edges are model-space curves only: `limn info` reports every face
/// trimmed, the curves made by inverting the edges and the proven bound (JSON and text).
#[test]
fn model_space_edges_are_reported_inverted_with_their_bound() {
    let v = info("fixtures/iges/occt/occ22470.igs", &[]);
    let f = &v["faces"];
    assert_eq!(f["faces"], 18);
    assert_eq!(f["untrimmed_surfaces"], 0);
    let inverted = f["inverted_curves"].as_u64().unwrap();
    let bound = f["inversion_distance"].as_f64().unwrap();
    assert!(inverted >= 88, "{inverted}");
    // Above the file's resolution (its edges lie off their faces), below 1e-4 of its size.
    assert!(bound > 1e-5 && bound < 2e-2, "{bound}");
    let out = Command::new(env!("CARGO_BIN_EXE_limn"))
        .args(["info", "fixtures/iges/occt/occ22470.igs"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run limn");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(&format!(
            "inverted edges: {inverted} trimming curves made from model-space edges"
        )),
        "{text}"
    );
}
