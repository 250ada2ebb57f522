//! Stirring (the paper's section on 2D movements): the demonstrated path is sampled at equal arc-length
//! steps `d`, kept out of obstacles, timed by the demonstrated speed, and at every time step the
//! velocities of the faces around the current sample are preset to that speed along the path.
//!
//! Where the paper projects a sample inside an obstacle to the nearest fluid point, the stirrer here
//! keeps a clearance (every cell within `clearance_cells` of its cell holds fluid) and never jumps: a
//! stretch of the path that enters the cleared-out zone is replaced by the shortest way around inside the
//! stirrer's fluid region (8-neighbour Dijkstra on the cells, then shortened to straight segments that
//! stay clear), so the stream the particle follows goes around the obstacle on one side. A path end inside
//! the zone is moved to the nearest reachable clear point.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use nalgebra::Vector2;

use super::boundary::{Component, FacePreset};
use super::error::FluidError;
use super::flags::Flags;
use super::path::{ArcPath, SpeedPath};
use super::raster::{cells_on_segment, distance_to_cell, nearest_in_cell};

/// How to stir.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StirringSettings {
    /// The arc-length step `d` of the samples, in cell sides.
    pub step_cells: f64,
    /// The stirrer stays in cells whose neighbours up to this many cells away (8-neighbourhood rings)
    /// all hold fluid.
    pub clearance_cells: usize,
    /// Faces within this distance of the current sample get the preset velocity, in cell sides.
    pub preset_radius_cells: f64,
    /// The pull of the preset toward the current sample: a face at distance `r` from the sample gets, on
    /// top of the demonstrated velocity, `attraction * speed * r / radius` toward the sample (zero at the
    /// sample itself, so a particle there moves at exactly the demonstrated velocity). 0 is the paper's
    /// plain preset, which carries a particle only as long as it stays inside the preset faces.
    pub attraction: f64,
}

impl Default for StirringSettings {
    /// `d` a quarter cell, one cell of clearance, presets within 1.5 cells, attraction 0.5.
    fn default() -> Self {
        Self { step_cells: 0.25, clearance_cells: 1, preset_radius_cells: 1.5, attraction: 0.5 }
    }
}

impl StirringSettings {
    /// Checks every field; names the first bad one.
    pub fn validate(&self) -> Result<(), FluidError> {
        if !(self.step_cells.is_finite() && self.step_cells > 0.0 && self.step_cells <= 1.0) {
            return Err(FluidError::invalid(
                "stirring.step_cells",
                format!("must be in (0, 1], got {}", self.step_cells),
            ));
        }
        if !(self.preset_radius_cells.is_finite() && (0.5..=8.0).contains(&self.preset_radius_cells)) {
            return Err(FluidError::invalid(
                "stirring.preset_radius_cells",
                format!("must be in [0.5, 8], got {}", self.preset_radius_cells),
            ));
        }
        if !(self.attraction.is_finite() && (0.0..=10.0).contains(&self.attraction)) {
            return Err(FluidError::invalid(
                "stirring.attraction",
                format!("must be in [0, 10], got {}", self.attraction),
            ));
        }
        if self.clearance_cells > 8 {
            return Err(FluidError::invalid(
                "stirring.clearance_cells",
                format!("must be at most 8, got {}", self.clearance_cells),
            ));
        }
        Ok(())
    }
}

/// The stirrer's path through the fluid, timed: equal arc-length samples with their speeds.
#[derive(Clone, Debug)]
pub struct Stirrer {
    route: ArcPath,
    samples: Vec<Vector2<f64>>,
    h_m: f64,
    radius_m: f64,
    attraction: f64,
    /// Stretches of the path replaced by a way around the cleared-out zone.
    pub detours: usize,
    /// Samples of the demonstrated path that lay in the cleared-out zone or another fluid region.
    pub moved_samples: usize,
}

impl Stirrer {
    /// Plans the stirring of `path` (grid coordinates, m) on `flags`' grid.
    pub fn plan(path: &SpeedPath, flags: &Flags, settings: &StirringSettings) -> Result<Self, FluidError> {
        settings.validate()?;
        let h = flags.grid.h_m;
        let d = settings.step_cells * h;
        let clear = Clearance::new(flags, settings.clearance_cells);
        let samples = ArcPath::new(path).sample_equal(d);
        let first = samples[0];
        let start = clear.nearest(first.point_m, None).ok_or_else(|| {
            FluidError::NoRoom(format!(
                "no cell with {} cells of fluid around it anywhere in the grid",
                settings.clearance_cells
            ))
        })?;
        let region = clear.region_at(start).unwrap_or(u32::MAX);
        let good = |p: Vector2<f64>| clear.region_at(p) == Some(region);
        let mut route: Vec<(Vector2<f64>, f64)> = vec![(start, first.speed_mps)];
        let mut detours = 0;
        let mut moved = 0;
        for sample in &samples {
            if !good(sample.point_m) {
                moved += 1;
                continue;
            }
            let (last, last_speed) = route[route.len() - 1];
            if clear.segment_clear(last, sample.point_m) {
                route.push((sample.point_m, sample.speed_mps));
            } else {
                detours += 1;
                clear.detour(last, last_speed, sample.point_m, sample.speed_mps, region, &mut route);
            }
        }
        let last_sample = samples[samples.len() - 1];
        if !good(last_sample.point_m) {
            let (last, last_speed) = route[route.len() - 1];
            if let Some(end) = clear.nearest(last_sample.point_m, Some(region)) {
                detours += 1;
                clear.detour(last, last_speed, end, last_sample.speed_mps, region, &mut route);
            }
        }
        let points: Vec<Vector2<f64>> = route.iter().map(|r| r.0).collect();
        let speeds: Vec<f64> = route.iter().map(|r| r.1).collect();
        let route = if points.len() >= 2 && points.windows(2).any(|w| w[0] != w[1]) {
            ArcPath::new(&SpeedPath { points_m: points, speed_mps: speeds })
        } else {
            // Nowhere to go: stir in place for as long as the demonstration lasted.
            return Err(FluidError::NoRoom(format!(
                "the path cannot leave its start at ({:.4}, {:.4}) m: no clear fluid around it",
                start.x, start.y
            )));
        };
        let samples = route.sample_equal(d).iter().map(|s| s.point_m).collect();
        Ok(Self {
            route,
            samples,
            h_m: h,
            radius_m: settings.preset_radius_cells * h,
            attraction: settings.attraction,
            detours,
            moved_samples: moved,
        })
    }

    /// Time the stirring takes, s.
    pub fn duration_s(&self) -> f64 {
        self.route.duration_s()
    }

    /// Length of the stirring path, m.
    pub fn length_m(&self) -> f64 {
        self.route.length_m()
    }

    /// The stirring path's equal arc-length samples, grid coordinates, m.
    pub fn samples(&self) -> &[Vector2<f64>] {
        &self.samples
    }

    /// Where the stirrer is at `t_s`, grid coordinates, m.
    pub fn position_at(&self, t_s: f64) -> Vector2<f64> {
        self.route.at_time(t_s).point_m
    }

    /// The stirrer at `t_s`: position (m), unit direction along the path (the chord over one cell of arc
    /// length) and speed (m/s).
    pub fn state_at(&self, t_s: f64) -> (Vector2<f64>, Vector2<f64>, f64) {
        let here = self.route.at_time(t_s);
        let half = 0.5 * self.h_m;
        let ahead = self.route.at(here.s_m + half).point_m;
        let behind = self.route.at(here.s_m - half).point_m;
        let chord = ahead - behind;
        let direction = if chord.norm() > 0.0 { chord.normalize() } else { Vector2::zeros() };
        (here.point_m, direction, here.speed_mps)
    }

    /// The preset velocities at `t_s`: every face between two fluid cells within the preset radius of
    /// the stirrer gets the component normal to it of `speed * direction`, plus the attraction toward
    /// the stirrer.
    pub fn presets_at(&self, t_s: f64, flags: &Flags) -> Vec<FacePreset> {
        let (centre, direction, speed) = self.state_at(t_s);
        let pull = self.attraction * speed / self.radius_m;
        let velocity = |at: Vector2<f64>| direction * speed + (centre - at) * pull;
        let grid = flags.grid;
        let (n, h) = (grid.n as isize, grid.h_m);
        let r = self.radius_m;
        let mut presets = Vec::new();
        let lo_i = ((centre.x - r) / h).floor() as isize - 1;
        let hi_i = ((centre.x + r) / h).ceil() as isize + 1;
        let lo_j = ((centre.y - r) / h).floor() as isize - 1;
        let hi_j = ((centre.y + r) / h).ceil() as isize + 1;
        for j in lo_j.max(1)..=hi_j.min(n) {
            for i in lo_i.max(1)..=hi_i.min(n) {
                let k = grid.idx(i as usize, j as usize);
                let u_at = Vector2::new(i as f64 * h, (j as f64 - 0.5) * h);
                if flags.u_fluid[k] && (u_at - centre).norm() <= r {
                    presets.push(FacePreset {
                        component: Component::U,
                        index: k,
                        velocity_mps: velocity(u_at).x,
                    });
                }
                let v_at = Vector2::new((i as f64 - 0.5) * h, j as f64 * h);
                if flags.v_fluid[k] && (v_at - centre).norm() <= r {
                    presets.push(FacePreset {
                        component: Component::V,
                        index: k,
                        velocity_mps: velocity(v_at).y,
                    });
                }
            }
        }
        presets
    }
}

/// The cells the stirrer may use: fluid with fluid all around up to the clearance, labelled by connected
/// region (4-neighbourhood).
struct Clearance {
    n: usize,
    h_m: f64,
    /// Per cell `j * n + i` (mask convention): its region, or `u32::MAX` when not clear.
    region: Vec<u32>,
}

impl Clearance {
    fn new(flags: &Flags, clearance: usize) -> Self {
        let grid = flags.grid;
        let n = grid.n;
        let c = clearance as isize;
        let fluid = |i: isize, j: isize| {
            i >= 0
                && j >= 0
                && i < n as isize
                && j < n as isize
                && flags.fluid[grid.idx(i as usize + 1, j as usize + 1)]
        };
        let mut ok = vec![false; n * n];
        for j in 0..n as isize {
            for i in 0..n as isize {
                ok[j as usize * n + i as usize] = (-c..=c).all(|dj| (-c..=c).all(|di| fluid(i + di, j + dj)));
            }
        }
        let mut region = vec![u32::MAX; n * n];
        let mut count = 0;
        let mut stack = Vec::new();
        for start in 0..n * n {
            if !ok[start] || region[start] != u32::MAX {
                continue;
            }
            region[start] = count;
            stack.push(start);
            while let Some(k) = stack.pop() {
                let (i, j) = (k % n, k / n);
                let mut push = |kk: usize| {
                    if ok[kk] && region[kk] == u32::MAX {
                        region[kk] = count;
                        stack.push(kk);
                    }
                };
                if i > 0 {
                    push(k - 1);
                }
                if i + 1 < n {
                    push(k + 1);
                }
                if j > 0 {
                    push(k - n);
                }
                if j + 1 < n {
                    push(k + n);
                }
            }
            count += 1;
        }
        Self { n, h_m: flags.grid.h_m, region }
    }

    fn cell(&self, i: isize, j: isize) -> Option<u32> {
        let n = self.n as isize;
        (i >= 0 && j >= 0 && i < n && j < n)
            .then(|| self.region[j as usize * self.n + i as usize])
            .filter(|r| *r != u32::MAX)
    }

    fn region_at(&self, p: Vector2<f64>) -> Option<u32> {
        let g = p / self.h_m;
        if !(g.x.is_finite() && g.y.is_finite()) {
            return None;
        }
        self.cell(g.x.floor() as isize, g.y.floor() as isize)
    }

    /// Whether the segment passes through clear cells of one region only.
    fn segment_clear(&self, a: Vector2<f64>, b: Vector2<f64>) -> bool {
        let Some(region) = self.region_at(a) else { return false };
        cells_on_segment(a, b, self.h_m, |i, j| self.cell(i, j) == Some(region))
    }

    /// The clear point (in `region`, or any) nearest to `p`, a hundredth of a cell inside its cell.
    fn nearest(&self, p: Vector2<f64>, region: Option<u32>) -> Option<Vector2<f64>> {
        let mut best: Option<(f64, isize, isize)> = None;
        for j in 0..self.n as isize {
            for i in 0..self.n as isize {
                let Some(r) = self.cell(i, j) else { continue };
                if region.is_some_and(|want| want != r) {
                    continue;
                }
                let dist = distance_to_cell(p, i, j, self.h_m);
                if best.is_none_or(|(b, _, _)| dist < b) {
                    best = Some((dist, i, j));
                }
            }
        }
        best.map(|(_, i, j)| nearest_in_cell(p, i, j, self.h_m, 0.01))
    }

    /// Appends to `route` the shortest way inside `region` from `from` (the route's last point) to `to`,
    /// its speed going linearly from `from_speed` to `to_speed` along it.
    fn detour(
        &self,
        from: Vector2<f64>,
        from_speed: f64,
        to: Vector2<f64>,
        to_speed: f64,
        region: u32,
        route: &mut Vec<(Vector2<f64>, f64)>,
    ) {
        let cells = self.shortest_cells(from, to, region);
        let mut points = vec![from];
        let h = self.h_m;
        // Interior cells of the chain by their centres; the ends are the points themselves.
        for &(i, j) in cells.iter().skip(1).take(cells.len().saturating_sub(2)) {
            points.push(Vector2::new((i as f64 + 0.5) * h, (j as f64 + 0.5) * h));
        }
        points.push(to);
        // Shorten: from each kept point, jump to the farthest point still in straight clear sight.
        let mut kept = vec![from];
        let mut at = 0;
        while at + 1 < points.len() {
            let mut next = at + 1;
            for candidate in (at + 2..points.len()).rev() {
                if self.segment_clear(points[at], points[candidate]) {
                    next = candidate;
                    break;
                }
            }
            kept.push(points[next]);
            at = next;
        }
        let length: f64 = kept.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        let mut along = 0.0;
        for w in kept.windows(2) {
            along += (w[1] - w[0]).norm();
            let f = if length > 0.0 { along / length } else { 1.0 };
            route.push((w[1], from_speed + (to_speed - from_speed) * f));
        }
    }

    /// Cells from `from`'s to `to`'s, 8-neighbour moves (diagonal only when both side cells are clear),
    /// Dijkstra; just the two cells when no way exists (cannot happen inside one region).
    fn shortest_cells(&self, from: Vector2<f64>, to: Vector2<f64>, region: u32) -> Vec<(isize, isize)> {
        let n = self.n as isize;
        let cell_of =
            |p: Vector2<f64>| ((p.x / self.h_m).floor() as isize, (p.y / self.h_m).floor() as isize);
        let (start, goal) = (cell_of(from), cell_of(to));
        let index = |(i, j): (isize, isize)| (j * n + i) as usize;
        let mut dist = vec![f64::INFINITY; self.n * self.n];
        let mut previous = vec![usize::MAX; self.n * self.n];
        let mut heap = BinaryHeap::new();
        let ok = |i: isize, j: isize| self.cell(i, j) == Some(region);
        if !ok(start.0, start.1) || !ok(goal.0, goal.1) {
            return vec![start, goal];
        }
        dist[index(start)] = 0.0;
        heap.push(Entry { cost: 0.0, cell: start });
        while let Some(Entry { cost, cell }) = heap.pop() {
            if cell == goal {
                break;
            }
            if cost > dist[index(cell)] {
                continue;
            }
            let (i, j) = cell;
            for (di, dj) in [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)] {
                let (ni, nj) = (i + di, j + dj);
                if !ok(ni, nj) || (di != 0 && dj != 0 && !(ok(i + di, j) && ok(i, j + dj))) {
                    continue;
                }
                let step = if di != 0 && dj != 0 { std::f64::consts::SQRT_2 } else { 1.0 };
                let next = cost + step;
                if next < dist[index((ni, nj))] {
                    dist[index((ni, nj))] = next;
                    previous[index((ni, nj))] = index(cell);
                    heap.push(Entry { cost: next, cell: (ni, nj) });
                }
            }
        }
        if previous[index(goal)] == usize::MAX && start != goal {
            return vec![start, goal];
        }
        let mut chain = vec![goal];
        let mut k = index(goal);
        while k != index(start) {
            k = previous[k];
            chain.push(((k as isize) % n, (k as isize) / n));
        }
        chain.reverse();
        chain
    }
}

/// A Dijkstra queue entry, smallest cost first (ties by cell, for a deterministic order).
#[derive(Clone, Copy, PartialEq)]
struct Entry {
    cost: f64,
    cell: (isize, isize),
}

impl Eq for Entry {}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.cost.total_cmp(&self.cost).then_with(|| other.cell.cmp(&self.cell))
    }
}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
