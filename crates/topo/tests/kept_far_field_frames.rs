//! [`FarField`]: a stroke's kept far field gives its frames the result
//! they get without it. A plate pushed into a row of balls cuts them
//! into more pieces than one pass over the triangles serves
//! (`winding::FEW_POINTS` samples), so the frame reads the far field from
//! the kept octree, told after every frame what the frame changed; the
//! same frames without it build an octree at every ask. The results are
//! the same meshes.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{EVERY_ASK_FROM, FarField, Options, TriMesh, topology_change_guarded_holding};

/// `m` stretched into the box from `lo` to `hi`.
fn fitted(m: &TriMesh, lo: DVec3, hi: DVec3) -> TriMesh {
    let (a, b) = used_bounds(m);
    map_positions(m, |p| lo + (p - a) / (b - a) * (hi - lo))
}

/// The scene: three rows of eight balls along x (at y = 0, 3 and 6), a
/// plate over each, and a big ball off to the side (so that a frame's
/// region, and all the frames' changes, are a small part of the mesh);
/// and each plate's box.
fn scene() -> (TriMesh, Vec<(DVec3, DVec3)>) {
    // Fine enough that the rows, where the frames change the surface, are
    // a small share of it.
    scene_with("@sphere:6")
}

/// [`scene`] with the big ball `big`.
fn scene_with(big: &str) -> (TriMesh, Vec<(DVec3, DVec3)>) {
    let ball = primitive("@sphere:2");
    let mut m = fitted(
        &primitive(big),
        DVec3::new(-6.0, -1.0, -1.0),
        DVec3::new(-4.0, 1.0, 1.0),
    );
    let mut plates = Vec::new();
    for row in 0..3 {
        let y = 3.0 * f64::from(row);
        for i in 0..8 {
            let x = 0.5 * f64::from(i);
            m.append(&fitted(
                &ball,
                DVec3::new(x - 0.15, y - 0.15, -0.15),
                DVec3::new(x + 0.15, y + 0.15, 0.15),
            ));
        }
        let plate = (
            DVec3::new(-0.4, y - 0.3, 0.2),
            DVec3::new(3.9, y + 0.3, 0.3),
        );
        m.append(&fitted(&primitive("@cube:8"), plate.0, plate.1));
        plates.push(plate);
    }
    (m, plates)
}

/// The vertices of `m` in the box `(lo, hi)` moved down by `dz`.
fn pushed(m: &TriMesh, (lo, hi): (DVec3, DVec3), dz: f64) -> Vec<DVec3> {
    m.positions
        .iter()
        .map(|&p| {
            if p.cmpge(lo).all() && p.cmple(hi).all() {
                p - DVec3::Z * dz
            } else {
                p
            }
        })
        .collect()
}

/// Each frame pushes one plate into its row of balls, cutting them and
/// the plate into more pieces than one pass serves; the first frame
/// builds the kept field, the later ones read it, told what the earlier
/// ones changed.
#[test]
fn plates_pushed_into_rows_of_balls_read_their_kept_far_field() {
    let (start, plates) = scene();
    assert!(closed_oriented(&start));
    let far = FarField::new();
    let (mut with, mut without) = (start.clone(), start.clone());
    for (frame, &plate) in plates.iter().enumerate() {
        // A plate is where it began until its frame.
        let end = pushed(&with, plate, 0.15);
        let r =
            topology_change_guarded_holding(&mut with, &end, &Options::default(), &[], Some(&far))
                .expect("a valid frame");
        assert!(!r.local.positions_only, "frame {frame} fuses");
        if let Some(b) = r.local.changed {
            far.changed_within(b);
        }
        assert!(far.is_built(), "frame {frame} read the kept field");
        let end = pushed(&without, plate, 0.15);
        topology_change_guarded_holding(&mut without, &end, &Options::default(), &[], None)
            .expect("a valid frame");
        assert_eq!(with, without, "frame {frame}: the same result");
        assert!(closed_oriented(&with), "frame {frame}");
    }
    // Built once, read by the later frames.
    assert_eq!(far.builds(), 1);
    // Each plate fused with its row: the big ball and three pieces.
    assert_eq!(components(&with), 4);
}

/// On a surface of at least [`EVERY_ASK_FROM`] triangles a built field
/// answers asks of any size. The first frame pushes a plate into a row of
/// balls (more samples than one pass serves: the field is built); the
/// second pushes a small plate into one ball, whose few pieces one pass
/// would serve on a smaller surface, and the kept field answers it. The
/// results are those of the same frames without a field.
#[test]
fn a_few_samples_on_a_large_surface_read_the_built_field() {
    let (start, plates, small) = large_scene();
    let far = FarField::new();
    let (mut with, mut without) = (start.clone(), start.clone());
    for (frame, plate) in [plates[0], small].into_iter().enumerate() {
        let answered = far.answers();
        frame_both(&mut with, &mut without, &far, plate, frame);
        assert!(far.answers() > answered, "frame {frame} read the field");
    }
    assert_eq!(far.builds(), 1);
}

/// A field prepared on a large surface ([`FarField::prepare`]) is built
/// beside the frames, and the first frame's few samples read it: the lone
/// ball's frame first, then the row's.
#[test]
fn a_prepared_field_answers_the_first_frame() {
    let (start, plates, small) = large_scene();
    let far = FarField::new();
    let (mut with, mut without) = (start.clone(), start.clone());
    for (frame, plate) in [small, plates[0]].into_iter().enumerate() {
        far.prepare(&with);
        let answered = far.answers();
        frame_both(&mut with, &mut without, &far, plate, frame);
        assert!(far.answers() > answered, "frame {frame} read the field");
    }
    // Built once, from `prepare`, and not again: the first frame's
    // changes were told to the build in progress.
    assert_eq!(far.builds(), 1);
}

/// One frame pushing `plate` into `with` (reading `far`, told what the
/// frame changed) and into `without` (without a field): the same result,
/// closed and fused.
fn frame_both(
    with: &mut TriMesh,
    without: &mut TriMesh,
    far: &FarField,
    plate: (DVec3, DVec3),
    frame: usize,
) {
    let end = pushed(with, plate, 0.15);
    let r = topology_change_guarded_holding(with, &end, &Options::default(), &[], Some(far))
        .expect("a valid frame");
    assert!(!r.local.positions_only, "frame {frame} fuses");
    if let Some(b) = r.local.changed {
        far.changed_within(b);
    }
    let end = pushed(without, plate, 0.15);
    topology_change_guarded_holding(without, &end, &Options::default(), &[], None)
        .expect("a valid frame");
    assert_eq!(with, without, "frame {frame}: the same result");
    assert!(closed_oriented(with), "frame {frame}");
}

/// [`scene`], past [`EVERY_ASK_FROM`] triangles, and a lone ball with a
/// small plate over it (whose frame cuts few pieces); the row plates,
/// and the small plate's box.
fn large_scene() -> (TriMesh, Vec<(DVec3, DVec3)>, (DVec3, DVec3)) {
    let (mut start, plates) = scene();
    let lone = (DVec3::new(6.85, -0.15, -0.15), DVec3::new(7.15, 0.15, 0.15));
    start.append(&fitted(&primitive("@sphere:2"), lone.0, lone.1));
    let small = (DVec3::new(6.8, -0.2, 0.2), DVec3::new(7.2, 0.2, 0.3));
    start.append(&fitted(&primitive("@cube:8"), small.0, small.1));
    assert!(start.triangles.len() >= EVERY_ASK_FROM);
    assert!(closed_oriented(&start));
    (start, plates, small)
}

/// Below [`EVERY_ASK_FROM`] triangles a frame with a few samples sums
/// them in one pass, even with a field built: the small plate pushed
/// into a lone ball after the first row's frame.
#[test]
fn a_few_samples_on_a_smaller_surface_take_one_pass() {
    let (mut start, plates) = scene_with("@sphere:3");
    let lone = (DVec3::new(6.85, -0.15, -0.15), DVec3::new(7.15, 0.15, 0.15));
    start.append(&fitted(&primitive("@sphere:2"), lone.0, lone.1));
    let small = (DVec3::new(6.8, -0.2, 0.2), DVec3::new(7.2, 0.2, 0.3));
    start.append(&fitted(&primitive("@cube:8"), small.0, small.1));
    assert!(start.triangles.len() < EVERY_ASK_FROM);
    let far = FarField::new();
    let mut m = start;
    let mut answers = Vec::new();
    for plate in [plates[0], small] {
        let end = pushed(&m, plate, 0.15);
        let r = topology_change_guarded_holding(&mut m, &end, &Options::default(), &[], Some(&far))
            .expect("a valid frame");
        assert!(!r.local.positions_only);
        if let Some(b) = r.local.changed {
            far.changed_within(b);
        }
        answers.push(far.answers());
    }
    assert!(answers[0] >= 1, "the row's frame read the field");
    assert_eq!(answers[1], answers[0], "the lone ball's frame did not");
    assert!(closed_oriented(&m));
}
