//! Which knot a thread holds: per projection direction, the closed picture's crossings, its Gauss code
//! reduced by R1/R2/nugatory moves, the determinant and writhe, a knot type by the rules below; then
//! a vote across directions.
//!
//! Rules (per direction, on the reduced diagram's determinant `det` and writhe `w`):
//!
//! | det | writhe | knot |
//! |---|---|---|
//! | no crossing left | | unknot |
//! | 1 | any | unknot: crossings R1/R2 could not remove (an R3 would); every knot of up to 10 crossings has det > 1 |
//! | 3 | any | trefoil: a single throw (half knot) closed through the bite |
//! | 5 | \|w\| >= 3 | surgeons: the surgeon's double throw, which closes to the cinquefoil 5_1 (writhe +-5) |
//! | 5 | \|w\| < 3 | figure_eight (4_1, writhe 0) |
//! | 9 | \|w\| <= 2 | square: reef knot, trefoil # mirror trefoil (writhe 0) |
//! | 9 | \|w\| >= 4 | granny: trefoil # trefoil (writhe +-6) |
//! | 15 | \|w\| <= 4 | surgeons_knot: double throw then an opposite single throw, 5_1 # mirror 3_1 (writhe +-2) |
//! | other | | unknown |
//!
//! The writhe of a reduced alternating diagram is an invariant (Tait's flyping conjecture), which is
//! why it separates square from granny and double throw from figure-eight; the proper invariant is
//! the signature. A direction whose diagram keeps extra crossings (say one that needs R3) still votes
//! right through the determinant, and the writhe bands leave room for a stray crossing. The answer is
//! the knot most directions voted for.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::centreline::{KnotRegion, arc_lengths_m, validate};
use super::closure::ClosedPicture;
use super::crossings::{TooTangled, find_crossings};
use super::error::KnotError;
use super::gauss_code::GaussCode;
use super::invariants::determinant;
use super::projection::{Projection, directions};
use super::reduce::reduce;
use super::tightness::KnotSpan;

/// The knots we recognise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KnotType {
    /// No knot.
    Unknot,
    /// A single throw (half knot, overhand): 3_1.
    Trefoil,
    /// The figure-eight knot, 4_1.
    FigureEight,
    /// The surgeon's double throw (double overhand): the cinquefoil 5_1.
    Surgeons,
    /// Square (reef) knot: two opposite throws, 3_1 # mirror 3_1.
    Square,
    /// Granny knot: two like throws, 3_1 # 3_1.
    Granny,
    /// The surgeon's knot: a double throw then an opposite single throw, 5_1 # mirror 3_1.
    SurgeonsKnot,
    /// A knot outside this list, or a diagram the rules cannot place.
    Unknown,
}

impl KnotType {
    /// Every type, in a fixed order.
    pub const ALL: [KnotType; 8] = [
        KnotType::Unknot,
        KnotType::Trefoil,
        KnotType::FigureEight,
        KnotType::Surgeons,
        KnotType::Square,
        KnotType::Granny,
        KnotType::SurgeonsKnot,
        KnotType::Unknown,
    ];

    /// The snake_case name (as in JSON).
    pub fn name(self) -> &'static str {
        match self {
            KnotType::Unknot => "unknot",
            KnotType::Trefoil => "trefoil",
            KnotType::FigureEight => "figure_eight",
            KnotType::Surgeons => "surgeons",
            KnotType::Square => "square",
            KnotType::Granny => "granny",
            KnotType::SurgeonsKnot => "surgeons_knot",
            KnotType::Unknown => "unknown",
        }
    }

    /// The rules of this module's table: a knot type from a reduced diagram.
    pub fn from_invariants(crossings: usize, determinant: Option<u64>, writhe: i32) -> Self {
        if crossings == 0 {
            return KnotType::Unknot;
        }
        let w = writhe.unsigned_abs();
        match determinant {
            Some(1) => KnotType::Unknot,
            Some(3) => KnotType::Trefoil,
            Some(5) if w >= 3 => KnotType::Surgeons,
            Some(5) => KnotType::FigureEight,
            Some(9) if w <= 2 => KnotType::Square,
            Some(9) if w >= 4 => KnotType::Granny,
            Some(15) if w <= 4 => KnotType::SurgeonsKnot,
            _ => KnotType::Unknown,
        }
    }
}

impl std::fmt::Display for KnotType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What one projection direction saw.
#[derive(Debug, Clone, PartialEq)]
pub struct DirectionVote {
    /// The direction, towards the viewer (unit).
    pub direction: [f64; 3],
    /// Crossings of the closed picture before reduction (those found before the search stopped,
    /// when it was too tangled to search).
    pub raw_crossings: usize,
    /// Whether the picture was searched and reduced; `false` when it had more crossings than
    /// [`MAX_CROSSINGS`](super::crossings::MAX_CROSSINGS) or more pairs to look at than
    /// [`MAX_PAIR_TESTS`](super::crossings::MAX_PAIR_TESTS): it then votes `unknown`.
    pub searched: bool,
    /// Crossings left after R1/R2/nugatory reduction.
    pub crossings: usize,
    /// |Delta(-1)| of the diagram (`None` if too large to compute exactly).
    pub determinant: Option<u64>,
    /// Writhe of the reduced diagram.
    pub writhe: i32,
    /// The knot by the rules.
    pub knot: KnotType,
}

/// The answer for one centreline.
#[derive(Debug, Clone, PartialEq)]
pub struct Classification {
    /// The knot most directions voted for.
    pub knot: KnotType,
    /// Determinant seen by the representative direction (the winning direction with the fewest
    /// crossings left).
    pub determinant: Option<u64>,
    /// Writhe of the representative direction's reduced diagram.
    pub writhe: i32,
    /// Crossings left in the representative direction's reduced diagram.
    pub crossings: usize,
    /// Fraction of directions that voted for `knot`.
    pub agreement: f64,
    /// Index of the representative direction in `votes`.
    pub representative: usize,
    /// Every direction's vote.
    pub votes: Vec<DirectionVote>,
    /// Where the representative diagram's crossings sit on the thread; `None` for the unknot.
    pub span: Option<KnotSpan>,
}

/// The points times the power of two that brings their largest coordinate into [1, 2): the same
/// curve to the bit at another scale, so that its projections' products neither overflow (a
/// trefoil 1e160 m across) nor underflow (1e-200 m), and the same crossings at every scale.
fn scaled_to_unit(points: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
    let largest = points.iter().flat_map(|p| p.iter().map(|v| v.abs())).fold(0.0, f64::max);
    if largest == 0.0 || !largest.is_finite() {
        return points.to_vec();
    }
    // 2^-e for the largest's binary exponent e, applied in two halves so that neither overflows.
    let e = largest.log2().floor() as i32;
    let (first, second) = (2f64.powi(-e / 2), 2f64.powi(-(e - e / 2)));
    points.iter().map(|p| p * first * second).collect()
}

/// Classifies a thread's centreline (needle end first): closes it far from the knot and votes
/// across [`DIRECTIONS`](super::projection::DIRECTIONS) projections. The curve's scale does not matter (it is classified scaled
/// by a power of two to unit size); the span is measured on the points as given.
pub fn classify(points: &[Vector3<f64>]) -> Result<Classification, KnotError> {
    validate(points)?;
    let (scaled, points) = (scaled_to_unit(points), points);
    let region = KnotRegion::of(&scaled);
    let picture = |view: &Projection| ClosedPicture::new(&scaled, &region, view);
    let votes: Vec<DirectionVote> = directions().iter().map(|view| vote(view, &picture(view))).collect();
    // The vote: most directions; a tie goes to the type listed first in KnotType::ALL.
    let tally = |k: KnotType| votes.iter().filter(|v| v.knot == k).count();
    let knot = KnotType::ALL
        .into_iter()
        .max_by_key(|&k| (tally(k), std::cmp::Reverse(k)))
        .unwrap_or(KnotType::Unknown);
    let representative = (0..votes.len())
        .filter(|&i| votes[i].knot == knot)
        .min_by_key(|&i| (votes[i].crossings, votes[i].raw_crossings, i))
        .unwrap_or(0);
    let rep = &votes[representative];
    // The representative's diagram again (one direction's work; keeping all of them would hold
    // every direction's crossings at once).
    let span = match (knot, find_crossings(&picture(&directions()[representative]))) {
        (KnotType::Unknot, _) | (_, Err(_)) => None,
        (_, Ok(crossings)) => {
            let mut code = GaussCode::from_crossings(&crossings);
            reduce(&mut code);
            KnotSpan::from_crossings(points, &arc_lengths_m(points), &crossings, &code.crossing_ids())
        }
    };
    Ok(Classification {
        knot,
        determinant: rep.determinant,
        writhe: rep.writhe,
        crossings: rep.crossings,
        agreement: tally(knot) as f64 / votes.len() as f64,
        representative,
        span,
        votes,
    })
}

/// One direction's vote: its picture's crossings, reduced, and the rules; a picture too tangled to
/// search votes `unknown` with the crossings found before the search stopped.
fn vote(view: &Projection, picture: &ClosedPicture) -> DirectionVote {
    let d = view.direction;
    let direction = [d.x, d.y, d.z];
    match find_crossings(picture) {
        Err(TooTangled { crossings_found }) => DirectionVote {
            direction,
            raw_crossings: crossings_found,
            searched: false,
            crossings: crossings_found,
            determinant: None,
            writhe: 0,
            knot: KnotType::Unknown,
        },
        Ok(crossings) => {
            let mut code = GaussCode::from_crossings(&crossings);
            reduce(&mut code);
            let determinant = determinant(&code);
            let writhe = code.writhe();
            DirectionVote {
                direction,
                raw_crossings: crossings.len(),
                searched: true,
                crossings: code.crossings(),
                determinant,
                writhe,
                knot: KnotType::from_invariants(code.crossings(), determinant, writhe),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each row of the rules table maps crossings, determinant and writhe to its knot type, and every type's
    /// serde name is its snake_case name.
    #[test]
    fn rules_table() {
        use KnotType::*;
        let cases = [
            (0, Some(1), 0, Unknot),
            (4, Some(1), 2, Unknot),
            (3, Some(3), 3, Trefoil),
            (5, Some(5), -5, Surgeons),
            (4, Some(5), 0, FigureEight),
            (6, Some(9), 0, Square),
            (6, Some(9), -6, Granny),
            (7, Some(9), 3, Unknown),
            (8, Some(15), 2, SurgeonsKnot),
            (8, Some(15), 8, Unknown),
            (5, Some(7), 5, Unknown),
            (50, None, 0, Unknown),
        ];
        for (n, det, w, want) in cases {
            assert_eq!(KnotType::from_invariants(n, det, w), want, "{n} crossings, det {det:?}, writhe {w}");
        }
        // serde's names are the snake_case names.
        use serde::de::IntoDeserializer;
        for k in KnotType::ALL {
            let de: serde::de::value::StrDeserializer<'_, serde::de::value::Error> =
                k.name().into_deserializer();
            assert_eq!(KnotType::deserialize(de), Ok(k));
        }
        assert_eq!(FigureEight.name(), "figure_eight");
    }
}
