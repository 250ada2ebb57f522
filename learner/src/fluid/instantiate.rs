//! The 2D-primitive API: a demonstrated path in its plane, moved to a new site, regenerated there by
//! stirring a fluid along it and throwing a particle into the stream, around real and virtual obstacles;
//! the particle's path comes back as time-stamped points in the plane and in the world.

use nalgebra::{Isometry3, Vector2, Vector3};

use super::boundary::Walls;
use super::error::FluidError;
use super::flags::Flags;
use super::mask::ObstacleMask;
use super::params::{DonorCell, FluidParams, PressureSolverKind};
use super::particle::{FlowInterval, Particle};
use super::path::SpeedPath;
use super::plane::{GridRegion, PlaneFrame};
use super::raster::distance_to_cell;
use super::simulation::FluidSim;
use super::stirring::{Stirrer, StirringSettings};

/// A demonstrated 2D movement: the plane it was made in and the path in that plane's coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarDemonstration {
    /// The demonstration's plane in the world.
    pub plane: PlaneFrame,
    /// The path, plane coordinates, with its speeds.
    pub path: SpeedPath,
}

/// How to instantiate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstantiateSettings {
    /// The pressure solver.
    pub solver: PressureSolverKind,
    /// Viscosity as a cell Reynolds number: `nu = v_max h / cell_reynolds`.
    pub cell_reynolds: f64,
    /// Safety factor on the stable time step.
    pub tau: f64,
    /// The donor-cell parameter.
    pub donor_cell: DonorCell,
    /// The pressure solve leaves a divergence below this fraction of `v_max / h`.
    pub divergence_rel_tol: f64,
    /// The stirrer moves at most this many cell sides per step.
    pub max_advance_cells: f64,
    /// Stirring.
    pub stirring: StirringSettings,
    /// Time between two output points, s.
    pub output_dt_s: f64,
}

impl Default for InstantiateSettings {
    /// The direct solver, cell Reynolds number 4, tau 0.9, per-flux donor cell, divergence below 1e-9
    /// `v_max / h`, at most 0.9 cells per step, the default stirring, output every 10 ms.
    fn default() -> Self {
        Self {
            solver: PressureSolverKind::Direct,
            cell_reynolds: 4.0,
            tau: 0.9,
            donor_cell: DonorCell::Local { factor: 1.0 },
            divergence_rel_tol: 1e-9,
            max_advance_cells: 0.9,
            stirring: StirringSettings::default(),
            output_dt_s: 0.01,
        }
    }
}

impl InstantiateSettings {
    /// Checks every field; names the first bad one.
    pub fn validate(&self) -> Result<(), FluidError> {
        for (name, x) in [
            ("cell_reynolds", self.cell_reynolds),
            ("divergence_rel_tol", self.divergence_rel_tol),
            ("max_advance_cells", self.max_advance_cells),
            ("output_dt_s", self.output_dt_s),
        ] {
            if !(x.is_finite() && x > 0.0) {
                return Err(FluidError::invalid(name, format!("must be positive, got {x}")));
            }
        }
        self.stirring.validate()
    }
}

/// A point of the regenerated path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathPoint {
    /// Time from the start, s.
    pub t_s: f64,
    /// Position in the (moved) plane's coordinates, m.
    pub plane_m: Vector2<f64>,
    /// Position in the world, m.
    pub world_m: Vector3<f64>,
}

/// How an instantiation went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstantiationReport {
    /// Fluid time steps.
    pub steps: usize,
    /// Duration of the regenerated movement, s.
    pub duration_s: f64,
    /// Cell side, m.
    pub cell_m: f64,
    /// The fluid's viscosity, m^2/s.
    pub viscosity_m2ps: f64,
    /// The pressure solve's divergence tolerance, 1/s.
    pub divergence_tol_per_s: f64,
    /// Largest divergence left by any step, 1/s.
    pub max_divergence_per_s: f64,
    /// Cells blocked by the mask repair.
    pub repaired_cells: usize,
    /// Stretches of the path stirred around the cleared-out zone of obstacles.
    pub detours: usize,
    /// Path samples that lay in that zone.
    pub moved_samples: usize,
    /// Particle steps split to avoid crossing an obstacle or wall.
    pub particle_splits: usize,
    /// Particle steps it held still.
    pub particle_holds: usize,
    /// Distance between the particle and the stirrer at the end, m.
    pub end_gap_m: f64,
    /// Smallest distance of a particle position to an obstacle cell, m (infinite without obstacles).
    pub min_clearance_m: f64,
}

/// A regenerated 2D primitive.
#[derive(Clone, Debug)]
pub struct Instantiation {
    /// The plane at the new site.
    pub plane: PlaneFrame,
    /// The simulation's region in that plane.
    pub region: GridRegion,
    /// The obstacle mask simulated (the given one, repaired).
    pub mask: ObstacleMask,
    /// The regenerated path, every `output_dt_s`, the end included.
    pub points: Vec<PathPoint>,
    /// Every particle position with its time, plane coordinates: `(t_s, point)`.
    pub trace: Vec<(f64, Vector2<f64>)>,
    /// The stirring path (equal arc-length samples), plane coordinates, m.
    pub stirring_path_m: Vec<Vector2<f64>>,
    /// The final velocity at every cell centre, `j * n + i`, plane axes, m/s (zero in obstacles).
    pub cell_velocity_mps: Vec<Vector2<f64>>,
    /// The final pressure over density at every cell centre, `j * n + i`, m^2/s^2 (zero in obstacles).
    pub cell_pressure_m2ps2: Vec<f64>,
    /// The cells the caller gave as obstacles (before the repair), `j * n + i`.
    pub given_obstacles: Vec<bool>,
    /// How it went.
    pub report: InstantiationReport,
}

/// Regenerates `demo` at the site `new_world_from_demo_world` (a rigid motion of the world carrying the
/// demonstration's plane, and the path in it, to the new place), simulating on `region` (coordinates of
/// the moved plane) with `obstacles` (real and virtual, one mask; repaired to obey the solver's rule by
/// growing, never shrinking).
pub fn instantiate(
    demo: &PlanarDemonstration,
    new_world_from_demo_world: &Isometry3<f64>,
    region: &GridRegion,
    obstacles: &ObstacleMask,
    settings: &InstantiateSettings,
) -> Result<Instantiation, FluidError> {
    settings.validate()?;
    let region = GridRegion::new(region.origin_m, region.cell_m, region.n)?;
    let path = SpeedPath::new(demo.path.points_m.clone(), demo.path.speed_mps.clone())?;
    if obstacles.n != region.n {
        return Err(FluidError::invalid(
            "obstacles",
            format!("a {0} x {0} mask for a {1} x {1} region", obstacles.n, region.n),
        ));
    }
    let plane = demo.plane.moved(new_world_from_demo_world);
    let repair = ObstacleMask::new(obstacles.n, obstacles.blocked.clone())?.repaired();
    let h = region.cell_m;
    let local = SpeedPath {
        points_m: path.points_m.iter().map(|p| region.to_grid(p)).collect(),
        speed_mps: path.speed_mps.clone(),
    };
    let v_max = path.speed_mps.iter().fold(0.0f64, |m, v| m.max(*v));
    let params = FluidParams {
        viscosity_m2ps: v_max * h / settings.cell_reynolds,
        donor_cell: settings.donor_cell,
        tau: settings.tau,
        divergence_tol_per_s: settings.divergence_rel_tol * v_max / h,
        solver: settings.solver,
        max_sor_iterations: 100_000,
    };
    let mut sim = FluidSim::new(&repair.mask, h, Walls::default(), params)?;
    let flags = sim.flags().clone();
    let stirrer = Stirrer::plan(&local, &flags, &settings.stirring)?;
    let duration = stirrer.duration_s();
    if duration / settings.output_dt_s > 1e7 {
        return Err(FluidError::invalid(
            "output_dt_s",
            format!("{} s gives more than 10 million points over {duration:.3} s", settings.output_dt_s),
        ));
    }
    sim.set_presets(stirrer.presets_at(0.0, &flags))?;
    let mut particle = Particle::new(stirrer.position_at(0.0), 0.0);
    let mut max_divergence = 0.0f64;
    let mut t = 0.0;
    let advance_dt = settings.max_advance_cells * h / v_max;
    while t < duration {
        let mut dt = sim.stable_dt().min(advance_dt);
        if t + dt > duration - 1e-9 * duration {
            dt = duration - t;
        }
        let report = sim.step_with_presets(dt, stirrer.presets_at(t + dt, &flags))?;
        max_divergence = max_divergence.max(report.max_divergence_per_s);
        let (umax, vmax) = sim.max_speeds();
        let flow = FlowInterval {
            start: (sim.previous_u(), sim.previous_v()),
            end: (sim.u(), sim.v()),
            t0_s: t,
            t1_s: t + dt,
            max_speed_mps: umax.max(vmax).max(v_max),
        };
        particle.advance(&flags, &flow);
        t += dt;
    }
    let end_gap_m = (particle.position_m() - stirrer.position_at(duration)).norm();
    let min_clearance_m = min_clearance(&flags, &particle.trace);
    let to_plane = |p: &Vector2<f64>| region.to_plane(p);
    let trace: Vec<(f64, Vector2<f64>)> = particle.trace.iter().map(|(t, p)| (*t, to_plane(p))).collect();
    let points = resample(&trace, settings.output_dt_s, duration)
        .into_iter()
        .map(|(t_s, plane_m)| PathPoint { t_s, plane_m, world_m: plane.to_world(&plane_m) })
        .collect();
    let report = InstantiationReport {
        steps: sim.steps(),
        duration_s: duration,
        cell_m: h,
        viscosity_m2ps: params.viscosity_m2ps,
        divergence_tol_per_s: params.divergence_tol_per_s,
        max_divergence_per_s: max_divergence,
        repaired_cells: repair.added_cells,
        detours: stirrer.detours,
        moved_samples: stirrer.moved_samples,
        particle_splits: particle.splits,
        particle_holds: particle.holds,
        end_gap_m,
        min_clearance_m,
    };
    Ok(Instantiation {
        plane,
        region,
        mask: repair.mask,
        points,
        trace,
        stirring_path_m: stirrer.samples().iter().map(to_plane).collect(),
        cell_velocity_mps: cell_velocities(&sim),
        cell_pressure_m2ps2: cell_pressures(&sim),
        given_obstacles: obstacles.blocked.clone(),
        report,
    })
}

/// Positions at `0, dt, 2 dt, ...` and at `end`, linear between the traced positions (whose straight
/// segments were checked against the obstacles, so the resampled path stays out of them too).
fn resample(trace: &[(f64, Vector2<f64>)], dt: f64, end: f64) -> Vec<(f64, Vector2<f64>)> {
    let count = (end / dt).floor() as usize;
    let mut times: Vec<f64> = (0..=count).map(|k| k as f64 * dt).collect();
    if end - count as f64 * dt > 1e-9 * dt {
        times.push(end);
    }
    let mut k = 0;
    times
        .into_iter()
        .map(|t| {
            while k + 2 < trace.len() && trace[k + 1].0 <= t {
                k += 1;
            }
            let (ta, a) = trace[k];
            let (tb, b) = trace[(k + 1).min(trace.len() - 1)];
            let f = if tb > ta { ((t - ta) / (tb - ta)).clamp(0.0, 1.0) } else { 1.0 };
            (t, a + (b - a) * f)
        })
        .collect()
}

/// Smallest distance from a traced position to an obstacle cell, m.
fn min_clearance(flags: &Flags, trace: &[(f64, Vector2<f64>)]) -> f64 {
    let grid = flags.grid;
    let edge: Vec<(isize, isize)> = flags
        .boundary
        .iter()
        .map(|(k, _)| ((k % grid.stride()) as isize - 1, (k / grid.stride()) as isize - 1))
        .collect();
    trace
        .iter()
        .flat_map(|(_, p)| edge.iter().map(move |&(i, j)| distance_to_cell(*p, i, j, grid.h_m)))
        .fold(f64::INFINITY, f64::min)
}

/// The pressure at every cell centre, mask order (zero in obstacles).
fn cell_pressures(sim: &FluidSim) -> Vec<f64> {
    let grid = sim.grid();
    let mut out = Vec::with_capacity(grid.n * grid.n);
    for j in 0..grid.n {
        for i in 0..grid.n {
            let k = grid.idx(i + 1, j + 1);
            out.push(if sim.flags().fluid[k] { sim.p()[k] } else { 0.0 });
        }
    }
    out
}

/// The velocity at every cell centre, mask order.
fn cell_velocities(sim: &FluidSim) -> Vec<Vector2<f64>> {
    let grid = sim.grid();
    let h = grid.h_m;
    let mut out = Vec::with_capacity(grid.n * grid.n);
    for j in 0..grid.n {
        for i in 0..grid.n {
            let fluid = sim.flags().fluid[grid.idx(i + 1, j + 1)];
            let centre = Vector2::new((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
            out.push(if fluid { sim.velocity_at(centre) } else { Vector2::zeros() });
        }
    }
    out
}
