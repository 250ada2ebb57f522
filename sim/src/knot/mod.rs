//! Knot evaluation from a thread's centreline: topology (which knot), tightness, and the verdict
//! Monte Carlo tallies. Pure geometry: usable on a simulated thread now and a reconstructed one later.
