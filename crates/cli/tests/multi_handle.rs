//! `holey handle --faces` on a real body (issue 18): faces that look at a
//! common point from outside are joined through a hub there with no
//! crossing (counted by `holey selfint`, the engine's exact count); faces
//! all around the body, looking outward, are refused naming faces in the
//! file's numbers, and nothing is written.

mod common;

use common::{ok, refused};
use serde_json::Value;

fn json(args: &[&str]) -> Value {
    serde_json::from_str(&ok(args)).expect("--json prints JSON")
}

#[test]
fn spot_gets_a_clean_hub_above_its_head_and_refuses_one_inside_it() {
    let dir = holey_testkit::shared_meshes_or_return!(
        "spot_gets_a_clean_hub_above_its_head_and_refuses_one_inside_it"
    );
    let tmp = tempfile::tempdir().expect("a temporary directory");
    let out = tmp.path().join("spot_hub.obj");
    let out = out.to_str().expect("a UTF-8 path");
    // The selection on the coarse cow: horns, ears, a hoof, the
    // tail end and the muzzle, all looking outward; the old hub sat inside
    // the cow (329 crossing pairs). Refused, naming faces, nothing written.
    let control = dir.join("spot_control_mesh.obj");
    let control = control.to_str().expect("a UTF-8 path");
    let err = refused(&[
        "handle",
        control,
        out,
        "--faces",
        "39,129,59,26,89,56",
        "--segments",
        "3",
        "--hub-scale",
        "0.3",
    ]);
    assert!(err.contains("look away from each other"), "{err}");
    assert!(err.contains("faces "), "{err}");
    assert!(!std::path::Path::new(out).exists());
    // Six quads of the finer cow around a point above its head: a horn,
    // both ears, the head, the neck and the back. Input: one closed piece,
    // genus 0, no crossing; output: one closed piece of genus 0 + 6 − 1.
    let quads = dir.join("spot_quadrangulated.obj");
    let quads = quads.to_str().expect("a UTF-8 path");
    assert_eq!(json(&["selfint", quads, "--json"])["intersecting_pairs"], 0);
    ok(&[
        "handle",
        quads,
        out,
        "--faces",
        "609,2067,2676,651,2136,933",
        "--segments",
        "4",
        "--hub-scale",
        "0.3",
        "--w1",
        "0.2",
        "--w2",
        "0.2",
    ]);
    assert_eq!(json(&["selfint", out, "--json"])["intersecting_pairs"], 0);
    let info = json(&["info", out, "--json"]);
    assert_eq!(info["genus"], 5);
    assert_eq!(info["components"], 1);
}
