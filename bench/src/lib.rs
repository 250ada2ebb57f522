//! knotlab's evaluation: Monte Carlo knot-tying runs (to come) and the performance benchmarks in
//! `benches/` (`cargo bench -p knotlab-bench`).
