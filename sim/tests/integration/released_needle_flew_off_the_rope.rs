//! Guards the released needle: with the suture as the rope, the needle is a body of its own with the
//! rope swaged to it. Dynamic and pulled by the rope's reaction alone once the jaws let go of it,
//! the 1 g needle and the rope's tension would feed each other step after step until the needle flew
//! off at 100 m/s (the scene stopped unhealthy); and the jaws' colliders, let loose on the swaged end
//! they had let through, would throw it out at 23 m/s. Let go, the needle rides on the rope's end,
//! and the jaws let the rope's end out gently.

use super::common;

use nalgebra::Vector3;

/// A released needle rides on the rope's end, within 2 mm of it and never faster than free fall, instead of
/// flying off.
#[test]
fn a_released_needle_stays_on_the_ropes_end() {
    let mut w = common::rope_world();
    for _ in 0..100 {
        w.step().expect("healthy while held");
    }
    w.release_all();
    let mut fastest_m_s: f64 = 0.0;
    for _ in 0..500 {
        w.step().expect("healthy after the release");
        let needle = w.suture().needle().body.expect("the needle's body");
        let v = w.physics().bodies[needle].linvel();
        fastest_m_s = fastest_m_s.max(Vector3::new(v.x, v.y, v.z).norm());
    }
    let rope = w.suture().as_rope().expect("the rope");
    assert!(rope.needle_free, "no jaws hold the needle: it rides on the rope");
    let needle = w.suture().needle().body.expect("the needle's body");
    let swage = w.physics().bodies[needle].translation();
    let off = (Vector3::new(swage.x, swage.y, swage.z) - rope.ropes.x[0]).norm();
    println!("fastest {fastest_m_s:.3} m/s; swage {:.3} mm off the rope's end", off * 1e3);
    // No faster than it would fall freely for the half second (4.9 m/s); measured 2.7 m/s.
    assert!(fastest_m_s < 9.81 * 0.5, "the needle moved at {fastest_m_s:.2} m/s");
    assert!(off < 0.002, "the needle lies {:.2} mm off the rope's end", off * 1e3);
}
