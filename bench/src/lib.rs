//! knotlab's evaluation: Monte Carlo knot-tying runs ([`mc`]) and the performance benchmarks in
//! `benches/` (`cargo bench -p knotlab-bench`).

pub mod mc;
pub mod report;
