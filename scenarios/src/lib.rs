//! knotlab's scenarios: scene files and their randomization, the scripted expert who demonstrates, and
//! the task patterns. It grows with the scenario issues; today it only fixes the crate's place in the
//! workspace (`hw`, `sim`, `learner` <- `scenarios`).
