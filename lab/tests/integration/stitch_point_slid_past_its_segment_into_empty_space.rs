//! Guards against a stitch point sliding past its segment into empty space. `Stitch::follow` hands
//! a point to the neighbouring segment only where the walk does not turn back; with a knot drawn
//! down onto the wound, the thread bends back right at the point, so a point held only on its
//! segment's axis line, free along it, slides on along the straight line past the segment's end:
//! under the holding test's load the flaps part 29 mm in 0.15 s while the thread between the two
//! points stays 12.5 mm long, the knot falling into the gap onto the pad, and every knot is judged
//! 28-34 mm open, "as far as the flaps' springs let it with no thread at all". A point slides only
//! 0.5 mm past its segment's end.

use crate::common::chain;
use knotlab_hw::rig::Rig;
use knotlab_lab::laid_knot::{LaidKnotParams, lay_and_snug};
use knotlab_sim::evaluate::hold_watched;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::tissue::Flap;

/// Under the holding load a stitch point slides no further than allowed past its segment's end, so the
/// flaps part no further than the thread between the stitch points lets them.
#[test]
fn the_flaps_part_no_further_than_the_thread_between_the_stitch_points_allows() {
    let scene = parse_scene(
        include_str!("../../../scenarios/short-suture-friction-0.5.toml"),
        "short-suture-friction-0.5.toml",
    )
    .expect("shipped scene");
    // A square knot laid 3 mm over the wound and drawn down onto it by its free ends at 1 N.
    let params = LaidKnotParams::default();
    let (mut world, _) =
        lay_and_snug(scene, Rig::shipped().expect("shipped rig"), &params).expect("laid and snugged");
    let evaluation = world.config().evaluation.clone();
    let mut worst_m = f64::NEG_INFINITY;
    let gap_m = hold_watched(&mut world, &evaluation, &mut |w, _| {
        let arc = |flap| {
            chain(w.suture())
                .stitch()
                .arc_at_m(w.physics(), chain(w.suture()).thread(), w.tissue(), flap)
                .expect("threaded")
        };
        let apart_m =
            (w.tissue().hole_m(w.physics(), Flap::A) - w.tissue().hole_m(w.physics(), Flap::B)).norm();
        worst_m = worst_m.max(apart_m - (arc(Flap::A) - arc(Flap::B)));
    })
    .expect("stable");
    println!(
        "wound {:.1} mm after the load; the points at most {:.2} mm further apart than the thread between them",
        gap_m * 1e3,
        worst_m * 1e3
    );
    // A point may run 0.5 mm past each end of its segment.
    assert!(worst_m < 0.0015, "the points drew {worst_m} m further apart than the thread between them");
}
