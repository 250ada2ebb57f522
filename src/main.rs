//! knotlab command line.
fn main() {}
