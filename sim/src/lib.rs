//! knotlab's simulated operating scene: the Rapier world (gantry, arms, instruments, suture, needle,
//! tissue) that implements the `knotlab-hw` device traits. It grows with the scene issue; today it only
//! fixes the crate's place in the workspace (`hw` <- `sim`).
