//! Guards against jaws closing on a thread that lies across them squeezing it along themselves
//! before they take it. Each jaw is a rigid capsule, so as they close they meet the thread long
//! before they are shut (opened 0.6 rad, 8 mm from the hinge, the room between their faces is
//! 1.7 mm), and their round faces push it: unclamped, a thread lying 0.4 rad off their hinge axis
//! slides 2-4 segments (6-12 mm) through them, and a presented tail, held taut, is pushed out
//! sideways (the second throw's take). Real jaws clamp it where their faces meet it; so do these
//! (`Grasp::squeezes`), holding it pressed between the faces.

use super::common;
use crate::common::chain;

use knotlab_hw::rig::ArmName;
use knotlab_sim::world::{JAW_CENTRE_OFFSET_M, SimWorld};
use nalgebra::{Point3, Vector3};
use rapier3d::prelude::*;

/// [`close_on_tilted`] with the thread along the hinge.
fn close_on_thread(jaw_rad: f64, from_hinge_m: f64, off_m: f64) -> (SimWorld, usize) {
    close_on_tilted(jaw_rad, from_hinge_m, off_m, 0.0)
}

/// Lays the thread across the left's jaws opened `jaw_rad`, along their hinge (turned `tilt_rad` from
/// it towards their tips), `from_hinge_m` out along them and `off_m` off their line across the
/// opening; closes them; returns the world and the thread's middle segment.
fn close_on_tilted(jaw_rad: f64, from_hinge_m: f64, off_m: f64, tilt_rad: f64) -> (SimWorld, usize) {
    let mut w = common::chain_world();
    let open = common::open_left_jaws(&mut w, jaw_rad);
    let tip = w.world_from_tip(ArmName::Left);
    // The hinge is twice the jaw-centre offset behind the tip, the jaws along the tip's z, opening
    // across its x, turning about its y.
    let at = tip * Point3::new(off_m, 0.0, from_hinge_m - 2.0 * JAW_CENTRE_OFFSET_M);
    let along = tip.rotation * Vector3::new(0.0, tilt_rad.cos(), tilt_rad.sin());
    let n = chain(w.suture()).thread().segments.len();
    // The middle segment's centre on the point.
    let start = at.coords
        - along
            * (chain(w.suture()).thread().segment_length_m * (n / 2) as f64
                + 0.5 * chain(w.suture()).thread().segment_length_m);
    let (suture, physics) = w.suture_and_physics_mut();
    chain(suture).thread().lay_straight(physics, &start, &along);
    common::close_left_weightless(&mut w, open, 300);
    (w, n / 2)
}

/// Jaws closing on a thread lying across them near their tips take the segment they meet and hold it between
/// their faces, not squeezed along or aside.
#[test]
fn closing_jaws_hold_a_thread_lying_across_them_near_their_tips() {
    for (from_hinge_m, off_m) in [(0.008, 0.0), (0.008, 0.0005), (0.009, -0.0005)] {
        let (w, middle) = close_on_thread(0.6, from_hinge_m, off_m);
        let segment = w.arm(ArmName::Left).held_at().unwrap_or_else(|| {
            panic!("{from_hinge_m} m out, {off_m} m off: closed empty ({:?})", w.events())
        });
        assert!(segment.abs_diff(middle) <= 1, "held segment {segment} of middle {middle}");
        // Held between the faces: its centre on the jaws' line across the opening.
        let tip = w.world_from_tip(ArmName::Left);
        let t = w.physics().bodies[chain(w.suture()).thread().segments[segment]].translation();
        let local = tip.inverse() * Point3::new(t.x, t.y, t.z);
        assert!(local.x.abs() < 3e-4, "{from_hinge_m} m out, {off_m} m off: held {} m across", local.x);
    }
}

/// Jaws closing on a thread lying aslant across them take the segment where they meet it, not one squeezed
/// several segments along.
#[test]
fn closing_jaws_hold_a_thread_lying_aslant_where_they_meet_it() {
    // Before: the jaws took the segment 2-4 from the middle (the thread squeezed along them).
    for (from_hinge_m, off_m) in [(0.007, 0.0), (0.008, 0.001), (0.009, 0.0)] {
        let (w, middle) = close_on_tilted(0.6, from_hinge_m, off_m, 0.4);
        let segment = w.arm(ArmName::Left).held_at().unwrap_or_else(|| {
            panic!("{from_hinge_m} m out, {off_m} m off: closed empty ({:?})", w.events())
        });
        assert!(segment.abs_diff(middle) <= 1, "held segment {segment} of middle {middle}");
    }
}

/// Jaws closing with the thread 6 mm across the opening from their line, outside them, hold nothing.
#[test]
fn jaws_closing_on_nothing_between_them_hold_nothing() {
    // The thread 6 mm across the opening from the jaws' line: outside the open jaws.
    let (w, _) = close_on_thread(0.6, 0.008, 0.006);
    assert!(w.arm(ArmName::Left).hold().is_none(), "{:?}", w.events());
}
