//! A picture of the scene around the wound in three orthographic views (top, front, side), drawn
//! with tiny-skia from the colliders themselves, so what is drawn is what collides: the thread
//! (blue at the needle end to orange at the tail), the needle (red), instrument shafts, wrists and
//! jaws (left green, right blue, assist purple, endoscope grey), the flaps (pink) and the pad (beige), the stitch points (green).

use nalgebra::{Point3, Vector3};
use tiny_skia::{Color, FillRule, LineCap, Paint, PathBuilder, Pixmap, Stroke, Transform};

use crate::shapes::{Owner, SolidShape, scene_shapes};
use crate::world::SimWorld;

/// How the picture is framed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Centre of every view, world frame, m.
    pub centre_m: Vector3<f64>,
    /// Half the width of each view, m.
    pub half_width_m: f64,
    /// Pixels per view side.
    pub pixels: u32,
}

impl View {
    /// Centred above the wound, 16 cm across, 480 pixels per view.
    pub fn around_wound(world: &SimWorld) -> Self {
        Self::around_wound_of_width(world, 0.08)
    }

    /// `half_width_m` either side, centred 3 cm above the wound or, for a narrower view, 0.6 of the
    /// half width above it, so that the wound stays in the picture.
    pub fn around_wound_of_width(world: &SimWorld, half_width_m: f64) -> Self {
        let up_m = 0.03f64.min(0.6 * half_width_m);
        let centre = world.tissue.world_from_tissue * Point3::new(0.0, 0.0, up_m);
        Self { centre_m: centre.coords, half_width_m, pixels: 480 }
    }
}

/// Why a picture could not be made.
#[derive(Debug, thiserror::Error)]
pub enum SnapshotError {
    /// The picture size is zero or too large.
    #[error("a snapshot of {0} pixels per view cannot be drawn")]
    Size(u32),
    /// PNG encoding failed.
    #[error("PNG encoding failed: {0}")]
    Encode(String),
}

/// Which world axes a view shows, right and up on the page.
const VIEWS: [(usize, usize); 3] = [(0, 1), (0, 2), (1, 2)];

struct Canvas<'a> {
    pixmap: &'a mut Pixmap,
    view: View,
}

impl Canvas<'_> {
    fn project(&self, panel: usize, p: &Vector3<f64>) -> (f32, f32) {
        let (right, up) = VIEWS[panel];
        let scale = f64::from(self.view.pixels) / (2.0 * self.view.half_width_m);
        let x = (p[right] - self.view.centre_m[right]) * scale + 0.5 * f64::from(self.view.pixels);
        let y = 0.5 * f64::from(self.view.pixels) - (p[up] - self.view.centre_m[up]) * scale;
        ((x + f64::from(self.view.pixels) * panel as f64) as f32, y as f32)
    }

    fn width_px(&self, metres: f64) -> f32 {
        (metres * f64::from(self.view.pixels) / (2.0 * self.view.half_width_m)).max(1.0) as f32
    }

    fn clip(&self, panel: usize) -> tiny_skia::Mask {
        let mut mask = tiny_skia::Mask::new(self.pixmap.width(), self.pixmap.height())
            .expect("the canvas has a non-zero size");
        let n = self.view.pixels as f32;
        if let Some(rect) = tiny_skia::Rect::from_xywh(n * panel as f32, 0.0, n, n) {
            mask.fill_path(&PathBuilder::from_rect(rect), FillRule::Winding, false, Transform::identity());
        }
        mask
    }

    fn polyline(&mut self, points: &[Vector3<f64>], width_m: f64, color: Color) {
        for panel in 0..3 {
            let mut pb = PathBuilder::new();
            for (k, p) in points.iter().enumerate() {
                let (x, y) = self.project(panel, p);
                if k == 0 { pb.move_to(x, y) } else { pb.line_to(x, y) }
            }
            if points.len() == 1 {
                let (x, y) = self.project(panel, &points[0]);
                pb.line_to(x + 0.01, y);
            }
            let Some(path) = pb.finish() else { continue };
            let mut paint = Paint::default();
            paint.set_color(color);
            paint.anti_alias = true;
            let stroke =
                Stroke { width: self.width_px(width_m), line_cap: LineCap::Round, ..Stroke::default() };
            let mask = self.clip(panel);
            self.pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), Some(&mask));
        }
    }

    fn outline(&mut self, corners: &[Vector3<f64>; 8], color: Color) {
        const EDGES: [(usize, usize); 12] =
            [(0, 1), (1, 3), (3, 2), (2, 0), (4, 5), (5, 7), (7, 6), (6, 4), (0, 4), (1, 5), (2, 6), (3, 7)];
        for (a, b) in EDGES {
            self.polyline(&[corners[a], corners[b]], 0.0003, color);
        }
    }
}

fn rgb(r: u8, g: u8, b: u8) -> Color {
    Color::from_rgba8(r, g, b, 255)
}

/// Draws the scene as it stands: three views side by side, returned as PNG bytes.
pub fn render_png(world: &SimWorld, view: &View) -> Result<Vec<u8>, SnapshotError> {
    render(world, view)?.encode_png().map_err(|e| SnapshotError::Encode(e.to_string()))
}

/// The picture of [`render_png`] as rows of RGB pixels, top row first: `3 * view.pixels` wide,
/// `view.pixels` high, three bytes a pixel.
pub fn render_rgb(world: &SimWorld, view: &View) -> Result<Vec<u8>, SnapshotError> {
    let pixmap = render(world, view)?;
    // Every pixel is opaque (the background is filled), so the premultiplied colour is the colour.
    Ok(pixmap.pixels().iter().flat_map(|p| [p.red(), p.green(), p.blue()]).collect())
}

fn render(world: &SimWorld, view: &View) -> Result<Pixmap, SnapshotError> {
    if view.pixels == 0 || view.pixels > 4096 {
        return Err(SnapshotError::Size(view.pixels));
    }
    let mut pixmap = Pixmap::new(3 * view.pixels, view.pixels).ok_or(SnapshotError::Size(view.pixels))?;
    pixmap.fill(rgb(250, 250, 250));
    let mut canvas = Canvas { pixmap: &mut pixmap, view: *view };
    let scene = scene_shapes(world);
    // Each arm in its own shade: left green, right blue, assist purple, endoscope grey.
    let color_of = |owner: &Owner| -> Color {
        match owner {
            Owner::Flap => rgb(220, 120, 150),
            Owner::Pad => rgb(200, 180, 140),
            Owner::Link(name) if name.starts_with("left") => rgb(90, 140, 100),
            Owner::Link(name) if name.starts_with("right") => rgb(80, 110, 160),
            Owner::Link(name) if name.starts_with("assist") => rgb(140, 100, 150),
            Owner::Link(_) | Owner::Other => rgb(110, 110, 120),
        }
    };
    // Solids: pad and flaps outlined, robot links as capsules or boxes.
    for solid in &scene.solids {
        let color = color_of(&solid.owner);
        match solid.shape {
            SolidShape::Cuboid { half_extents_m: h } => {
                let corners: [Vector3<f64>; 8] = std::array::from_fn(|k| {
                    let local = Vector3::new(
                        if k & 1 == 0 { -h.x } else { h.x },
                        if k & 2 == 0 { -h.y } else { h.y },
                        if k & 4 == 0 { -h.z } else { h.z },
                    );
                    solid.world_point(&local)
                });
                canvas.outline(&corners, color);
            }
            SolidShape::Capsule { a_m, b_m, radius_m } => {
                canvas.polyline(&[solid.world_point(&a_m), solid.world_point(&b_m)], 2.0 * radius_m, color);
            }
            SolidShape::Ball { radius_m } => {
                canvas.polyline(&[solid.world_point(&Vector3::zeros())], 2.0 * radius_m, color);
            }
        }
    }
    // The thread, coloured from the needle end (blue) to the tail (orange).
    let n = scene.thread_m.len().saturating_sub(1).max(1);
    for (k, w) in scene.thread_m.windows(2).enumerate() {
        let f = k as f32 / n as f32;
        let color =
            Color::from_rgba(0.1 + 0.85 * f, 0.35 + 0.2 * f, 0.9 - 0.8 * f, 1.0).unwrap_or(Color::BLACK);
        canvas.polyline(w, 2.0 * scene.thread_radius_m, color);
    }
    canvas.polyline(&scene.needle_m, 2.0 * scene.needle_radius_m, rgb(200, 30, 30));
    for hole in &scene.holes_m {
        canvas.polyline(&[*hole], 0.0012, rgb(20, 160, 60));
    }
    // Panel borders.
    for panel in 1..3 {
        let x = (panel * view.pixels as usize) as f32;
        let mut pb = PathBuilder::new();
        pb.move_to(x, 0.0);
        pb.line_to(x, view.pixels as f32);
        if let Some(path) = pb.finish() {
            let mut paint = Paint::default();
            paint.set_color(rgb(0, 0, 0));
            canvas.pixmap.stroke_path(&path, &paint, &Stroke::default(), Transform::identity(), None);
        }
    }
    Ok(pixmap)
}
