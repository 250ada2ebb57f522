//! A what-if for a throw before any physics: the thread as it would lie if the jaws holding the tail
//! drew it straight back along their axis, the rest of the tail following, so that [`super::classify()`]
//! can say which knot that draw would make. A turn wound round the jaws goes onto whatever they draw
//! back through it; whether that is a throw depends on how the turn and its legs lie (the first
//! throw's take checks out as `surgeons`; a second throw's turns, wound otherwise, need not).

use nalgebra::{UnitVector3, Vector3};

use super::error::KnotError;

/// The centreline with the tail (the points after `grip`, the far end last) replaced: the point on
/// the jaws' axis level with the grip point, then points every `step_m` back along the axis (against
/// `jaws`, which points from the hinge to the tips) for `length_m`. `axis_point_m` is any point on the
/// axis (the tip). The long end (the points before `grip`) is kept as it lies.
pub fn drawn_through(
    points: &[Vector3<f64>],
    grip: usize,
    axis_point_m: &Vector3<f64>,
    jaws: &UnitVector3<f64>,
    length_m: f64,
    step_m: f64,
) -> Result<Vec<Vector3<f64>>, KnotError> {
    if grip == 0 || grip >= points.len() {
        return Err(KnotError::GripOutOfRange { grip, count: points.len() });
    }
    if !(length_m.is_finite() && step_m.is_finite() && step_m > 0.0 && length_m >= step_m) {
        return Err(KnotError::BadDraw { length_m, step_m });
    }
    let on_axis = axis_point_m + jaws.into_inner() * (points[grip] - axis_point_m).dot(jaws);
    let steps = (length_m / step_m).floor() as usize;
    let mut drawn: Vec<Vector3<f64>> = points[..grip].to_vec();
    drawn.push(on_axis);
    drawn.extend((1..=steps).map(|k| on_axis - jaws.into_inner() * (k as f64 * step_m)));
    Ok(drawn)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The draw keeps the thread up to the grip, puts the next point on the jaws' axis level with the grip
    /// and lays the tail back along the jaws for the draw's length.
    #[test]
    fn the_tail_past_the_grip_is_replaced_by_a_line_back_along_the_jaws() {
        let points: Vec<Vector3<f64>> = (0..10).map(|i| Vector3::new(i as f64 * 0.003, 0.01, 0.0)).collect();
        let jaws = UnitVector3::new_normalize(Vector3::new(0.0, 0.0, 1.0));
        let tip = Vector3::new(0.012, 0.0, 0.02);
        let drawn = drawn_through(&points, 6, &tip, &jaws, 0.03, 0.003).unwrap();
        assert_eq!(drawn.len(), 6 + 1 + 10);
        assert_eq!(&drawn[..6], &points[..6]);
        // Level with the grip point along the jaws, on their axis; then back along them.
        assert!((drawn[6] - Vector3::new(0.012, 0.0, 0.0)).norm() < 1e-12, "{}", drawn[6]);
        assert!((drawn[16] - Vector3::new(0.012, 0.0, -0.03)).norm() < 1e-12, "{}", drawn[16]);
    }

    /// A grip at the thread's first point or past its last, a zero step or a non-finite draw is refused.
    #[test]
    fn a_grip_off_the_thread_or_a_bad_draw_is_refused() {
        let points: Vec<Vector3<f64>> = (0..5).map(|i| Vector3::new(i as f64, 0.0, 0.0)).collect();
        let jaws = UnitVector3::new_normalize(Vector3::x());
        let o = Vector3::zeros();
        assert_eq!(
            drawn_through(&points, 5, &o, &jaws, 1.0, 0.1),
            Err(KnotError::GripOutOfRange { grip: 5, count: 5 })
        );
        assert!(matches!(
            drawn_through(&points, 0, &o, &jaws, 1.0, 0.1),
            Err(KnotError::GripOutOfRange { .. })
        ));
        assert!(matches!(drawn_through(&points, 2, &o, &jaws, 1.0, 0.0), Err(KnotError::BadDraw { .. })));
        assert!(matches!(
            drawn_through(&points, 2, &o, &jaws, f64::NAN, 0.1),
            Err(KnotError::BadDraw { .. })
        ));
    }
}
