//! Knot evaluation from a thread's centreline: topology (which knot), tightness, and the verdict
//! Monte Carlo tallies. Pure geometry: usable on a simulated thread now and a reconstructed one later.
//!
//! The recipe (`shared/reference/knot-topology.md`): close the open thread far from the knot
//! ([`closure`]), look at it from [`projection::DIRECTIONS`] directions ([`projection`]), find the
//! crossings ([`crossings`]), write the signed Gauss code ([`gauss_code`]), simplify it ([`reduce`]),
//! compute the determinant and writhe ([`invariants`]), name the knot and vote ([`classify`](mod@classify)). Then
//! where the knot sits ([`tightness`]), how slack the loop's legs lie ([`legs`]), how much each end bends
//! inside the knot ([`bending`]) and the trial's
//! outcome ([`verdict`]). Centrelines come from the simulator or from a CSV file ([`csv`]); [`draw_through`]
//! asks which knot a draw of the tail back along the jaws would make.
//!
//! ```
//! use knotlab_sim::knot::{KnotType, classify};
//! use nalgebra::Vector3;
//!
//! // A trefoil torus knot, cut open on its outer rim: closed far away, it is a trefoil again.
//! let points: Vec<Vector3<f64>> = (0..120)
//!     .map(|i| {
//!         let t = std::f64::consts::TAU * i as f64 / 120.0;
//!         let r = 2.0 + (3.0 * t).cos();
//!         Vector3::new(r * (2.0 * t).cos(), r * (2.0 * t).sin(), (3.0 * t).sin())
//!     })
//!     .collect();
//! let found = classify(&points)?;
//! assert_eq!((found.knot, found.determinant), (KnotType::Trefoil, Some(3)));
//! # Ok::<(), knotlab_sim::knot::KnotError>(())
//! ```

pub mod bending;
pub mod centreline;
pub mod classify;
pub mod closure;
pub mod crossings;
pub mod csv;
pub mod draw_through;
pub mod error;
pub mod gauss_code;
pub mod invariants;
pub mod legs;
pub mod projection;
pub mod reduce;
pub mod tightness;
pub mod verdict;

pub use centreline::validate;
pub use classify::{Classification, DirectionVote, KnotType, classify};
pub use csv::{CsvError, LineProblem, read_points};
pub use draw_through::drawn_through;
pub use error::KnotError;
pub use tightness::{DownLimits, KnotPlacement, KnotSpan, TissueSurface};
pub use verdict::{FailureMode, StitchSite, Verdict, judge};
