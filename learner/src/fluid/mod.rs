//! 2D primitives through fluid dynamics (the paper's section on 2D movements): a 2D incompressible
//! Navier-Stokes solver after Griebel, Dornseifer and Neunhoeffer, "Numerical Simulation in Fluid
//! Dynamics" (SIAM 1997), stirred along a demonstrated path, and a particle thrown into the stream that
//! regenerates the path at a new site, around obstacles.
//!
//! The API for a 2D primitive is [`instantiate()`]: a [`PlanarDemonstration`] (a [`PlaneFrame`] and a
//! [`SpeedPath`] in its coordinates), the site as a rigid motion of the world, a [`GridRegion`] in the
//! moved plane and an [`ObstacleMask`] (real obstacles from [`GridRegion::block_box`] or
//! [`block_solid`], virtual obstacles OR-ed in with [`ObstacleMask::union`]); it returns the particle's
//! path as time-stamped plane and world points ([`Instantiation`]). The solver itself is [`FluidSim`]
//! (one adaptive step at a time, SOR or the direct pressure solve, walls that may slide, presets), and
//! [`run_cavity`] its validation against Ghia, Ghia and Shin (1982).

pub mod boundary;
pub mod cavity;
pub mod error;
pub mod flags;
pub mod grid;
pub mod instantiate;
pub mod mask;
pub mod momentum;
pub mod params;
pub mod particle;
pub mod path;
pub mod path_file;
pub mod plane;
pub mod pressure;
pub mod raster;
pub mod simulation;
pub mod solids;
pub mod stirring;
pub mod timestep;

pub use boundary::{Component, FacePreset, Walls};
pub use cavity::{CavityConfig, CavityRun, GHIA_U_Y, GHIA_V_X, run_cavity};
pub use error::FluidError;
pub use grid::StaggeredGrid;
pub use instantiate::{
    InstantiateSettings, Instantiation, InstantiationReport, PathPoint, PlanarDemonstration, instantiate,
};
pub use mask::{ObstacleMask, Repair};
pub use params::{DonorCell, FluidParams, PressureSolverKind};
pub use path::{ArcPath, ArcSample, SpeedPath};
pub use plane::{GridRegion, PlaneFrame};
pub use simulation::{FluidSim, StepReport};
pub use solids::{Solid, block_solid};
pub use stirring::{Stirrer, StirringSettings};
