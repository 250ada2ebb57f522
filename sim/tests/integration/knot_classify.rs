//! Knot classification on parametric threads: which knot, its determinant and writhe, robustness to
//! small perturbations, and degenerate input.

use std::f64::consts::{PI, TAU};

use knotlab_sim::knot::{
    Classification, DownLimits, FailureMode, KnotError, KnotType, StitchSite, TissueSurface, Verdict,
    classify, judge, read_points,
};
use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

type V = Vector3<f64>;

/// The (p, q) torus knot on a torus of radii 2 and 1, cut open at t = 0 (its outermost point).
fn torus_knot(p: f64, q: f64, n: usize) -> Vec<V> {
    (0..n)
        .map(|i| {
            let t = TAU * i as f64 / n as f64;
            let r = 2.0 + (q * t).cos();
            V::new(r * (p * t).cos(), r * (p * t).sin(), (q * t).sin())
        })
        .collect()
}

/// The figure-eight knot, cut open at its outermost point.
fn figure_eight(n: usize) -> Vec<V> {
    (0..n)
        .map(|i| {
            let t = TAU * i as f64 / n as f64;
            let r = 2.0 + (2.0 * t).cos();
            V::new(r * (3.0 * t).cos(), r * (3.0 * t).sin(), (4.0 * t).sin())
        })
        .collect()
}

/// An open overhand knot with both tails pointing along +x (a hairpin): the trefoil above, cut open
/// on its rim and its ends drawn out. `mirror` ties the other hand.
fn hairpin_overhand(mirror: bool, samples: usize) -> Vec<V> {
    let eps = 0.15;
    let mut points = vec![V::new(6.0, -1.2, 0.0), V::new(4.5, -1.1, 0.0), V::new(3.5, -1.0, -0.2)];
    for i in 0..=samples {
        let t = TAU - eps - (TAU - 2.0 * eps) * i as f64 / samples as f64;
        let r = 2.0 + (3.0 * t).cos();
        points.push(V::new(r * (2.0 * t).cos(), r * (2.0 * t).sin(), (3.0 * t).sin()));
    }
    points.extend([V::new(3.5, 1.0, 0.2), V::new(4.5, 1.1, 0.0), V::new(6.0, 1.2, 0.0)]);
    if mirror {
        for p in &mut points {
            p.z = -p.z;
        }
    }
    points
}

/// A big loop of thread (radius 14, cut open at angle pi) with open knots tied in it at the given
/// angles: each knot's hairpin points outward and its tails join the loop.
fn loop_with_knots(knots: &[(f64, Vec<V>)]) -> Vec<V> {
    const RIM: f64 = 14.0;
    let mut points = Vec::new();
    let mut angle = -PI + 0.3;
    while angle < PI - 0.3 {
        if let Some((at, knot)) = knots.iter().find(|(at, _)| (angle - (at - 0.2)).abs() < 0.05) {
            let (radial, tangent) = (V::new(at.cos(), at.sin(), 0.0), V::new(-at.sin(), at.cos(), 0.0));
            let centre = radial * (RIM - 6.0);
            points.extend(knot.iter().map(|p| centre + radial * p.x + tangent * p.y + V::z() * p.z));
            angle = at + 0.2;
        }
        points.push(V::new(RIM * angle.cos(), RIM * angle.sin(), 0.0));
        angle += 0.1;
    }
    points
}

/// An open overhand knot on a straight-ish thread: tails leave in opposite directions.
fn open_overhand() -> Vec<V> {
    let mut points = vec![
        V::new(-20.0, -6.0, 0.0),
        V::new(0.0, -6.0, 0.0),
        V::new(7.0, -5.0, 0.0),
        V::new(7.5, -2.0, 0.0),
    ];
    points.extend(hairpin_overhand(false, 90));
    points.push(V::new(20.0, 1.5, 0.0));
    points
}

/// A suture as tied: the bite (a loop under the tissue) joins the two strands at the bottom; each
/// throw is a horizontal twist of the two strands with the given number of half-twists (odd; the
/// sign is the hand: 3 for a single throw, 5 for a surgeon's double throw), throws stacked upward;
/// the two ends leave upward to the left (needle end) and right.
fn suture(twists: &[i32]) -> Vec<V> {
    #[derive(Clone, Copy, PartialEq, Debug)]
    enum End {
        WestTop,
        WestBottom,
        EastTop,
        EastBottom,
    }
    use End::*;
    const RHO: f64 = 0.5;
    const GAP: f64 = 3.0;
    let level = |r: usize| r as f64 * GAP;
    let top = twists.len() - 1;
    let y_top = level(top);
    let mut points = vec![
        V::new(-4.0, y_top + 6.0, 0.0),
        V::new(-2.5, y_top + 3.0, 0.0),
        V::new(-1.5, y_top + RHO + 0.4, 0.0),
    ];
    let (mut region, mut end) = (top, WestTop);
    for _ in 0..4 * twists.len() + 2 {
        let k = f64::from(twists[region]);
        let (strand, from_west) = match end {
            WestTop => (0.0, true),
            EastBottom => (0.0, false),
            WestBottom => (1.0, true),
            EastTop => (1.0, false),
        };
        let samples = 8 * twists[region].unsigned_abs() as usize + 4;
        for i in 0..=samples {
            let f = i as f64 / samples as f64;
            let x = if from_west { -1.0 + 2.0 * f } else { 1.0 - 2.0 * f };
            let phi = strand * PI + k * PI * (x + 1.0) / 2.0;
            points.push(V::new(x, level(region) + RHO * phi.cos(), RHO * phi.sin()));
        }
        let exit = match end {
            WestTop => EastBottom,
            EastBottom => WestTop,
            WestBottom => EastTop,
            EastTop => WestBottom,
        };
        let y = level(region);
        let side = |e: End| if matches!(e, WestTop | WestBottom) { -1.5 } else { 1.5 };
        match exit {
            EastTop if region == top => {
                points.extend([
                    V::new(1.5, y + RHO + 0.4, 0.0),
                    V::new(2.5, y + 3.0, 0.0),
                    V::new(4.0, y + 6.0, 0.0),
                ]);
                return points;
            }
            WestTop | EastTop => {
                let x = side(exit);
                points.extend([V::new(x, y + RHO + 0.4, 0.0), V::new(x, y + GAP - RHO - 0.4, 0.0)]);
                region += 1;
                end = if exit == WestTop { WestBottom } else { EastBottom };
            }
            WestBottom | EastBottom if region > 0 => {
                let x = side(exit);
                points.extend([V::new(x, y - RHO - 0.4, 0.0), V::new(x, y - GAP + RHO + 0.4, 0.0)]);
                region -= 1;
                end = if exit == WestBottom { WestTop } else { EastTop };
            }
            WestBottom | EastBottom => {
                // The bite, under the tissue.
                let x = side(exit);
                points.extend([
                    V::new(x, -RHO - 0.4, 0.0),
                    V::new(x, -3.0, 0.0),
                    V::new(-x, -3.0, 0.0),
                    V::new(-x, -RHO - 0.4, 0.0),
                ]);
                end = if exit == WestBottom { EastBottom } else { WestBottom };
            }
        }
    }
    panic!("the suture's strands do not lead to the tail: twists {twists:?} must all be odd");
}

/// The circle of radius 10 with small loops (kinks) every 30 degrees and a wavy height: only R1
/// crossings, cut open at its outermost point.
fn kinked_circle(n: usize) -> Vec<V> {
    (0..n)
        .map(|i| {
            let t = TAU * i as f64 / n as f64;
            V::new(
                10.0 * t.cos() + 1.5 * (12.0 * t).cos(),
                10.0 * t.sin() + 1.5 * (12.0 * t).sin(),
                0.4 * (12.0 * t + 1.0).sin() + 0.2 * (3.0 * t).sin(),
            )
        })
        .collect()
}

/// An ascending unknot: the (2,7) torus knot's shadow with overlapping loops added, its height
/// rising all the way along; cut open at its outermost point.
fn ascending_unknot(n: usize) -> Vec<V> {
    (0..n)
        .map(|i| {
            let t = TAU * i as f64 / n as f64;
            let r = 2.0 + (7.0 * t).cos();
            V::new(
                r * (2.0 * t).cos() + 0.45 * (16.0 * t).cos() - 0.45,
                r * (2.0 * t).sin() + 0.45 * (16.0 * t).sin(),
                0.5 * t,
            )
        })
        .collect()
}

fn show(name: &str, c: &Classification) -> String {
    let votes: Vec<String> = c
        .votes
        .iter()
        .map(|v| {
            format!(
                "{}({}->{}, det {:?}, w {})",
                v.knot, v.raw_crossings, v.crossings, v.determinant, v.writhe
            )
        })
        .collect();
    format!(
        "{name}: {} det {:?} writhe {} crossings {} agreement {:.2}\n  {}",
        c.knot,
        c.determinant,
        c.writhe,
        c.crossings,
        c.agreement,
        votes.join("\n  ")
    )
}

fn check(name: &str, points: &[V], knot: KnotType, det: u64, writhe_abs: u32) -> Classification {
    let c = classify(points).expect("a valid centreline");
    let text = show(name, &c);
    println!("{text}");
    assert_eq!(c.knot, knot, "{text}");
    assert_eq!(c.determinant, Some(det), "{text}");
    assert_eq!(c.writhe.unsigned_abs(), writhe_abs, "{text}");
    assert!(c.agreement >= 0.75, "{text}");
    c
}

/// A kinked circle and an ascending thread that draw many crossings both classify as the unknot.
#[test]
fn unknot_drawn_with_many_removable_crossings() {
    let kinked = classify(&kinked_circle(400)).expect("valid");
    let text = show("kinked circle", &kinked);
    println!("{text}");
    assert_eq!(kinked.knot, KnotType::Unknot, "{text}");
    assert!(kinked.votes.iter().any(|v| v.raw_crossings >= 12), "the loops must draw crossings: {text}");
    // Only kinks: R1 removes every crossing in most directions.
    assert!(kinked.votes.iter().filter(|v| v.crossings == 0).count() >= 10, "{text}");

    let ascending = classify(&ascending_unknot(600)).expect("valid");
    let text = show("ascending unknot", &ascending);
    println!("{text}");
    assert_eq!(ascending.knot, KnotType::Unknot, "{text}");
    assert!(ascending.votes.iter().map(|v| v.raw_crossings).sum::<usize>() >= 150, "{text}");
    assert!(ascending.agreement >= 0.9, "{text}");
    assert!(ascending.span.is_none());
}

/// Random ascending threads (height rising along the thread, so every one is an unknot, and its
/// closure far away keeps it ascending): some of their diagrams keep crossings that R1, R2 and
/// nugatory removal cannot take out (an R3 would be needed); the determinant rule calls them unknots.
#[test]
fn unknots_that_reduction_alone_cannot_simplify() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let (mut diagrams, mut kept_crossings) = (0, 0);
    for trial in 0..200 {
        let modes: Vec<[f64; 4]> =
            (0..5).map(|_| std::array::from_fn(|_| rng.random_range(-1.0..1.0))).collect();
        let points: Vec<V> = (0..300)
            .map(|i| {
                let t = TAU * i as f64 / 300.0;
                let (mut x, mut y) = (0.0, 0.0);
                for (k, m) in modes.iter().enumerate() {
                    let (c, s) = (((k + 1) as f64 * t).cos(), ((k + 1) as f64 * t).sin());
                    x += m[0] * c + m[1] * s;
                    y += m[2] * c + m[3] * s;
                }
                V::new(x, y, 0.3 * t)
            })
            .collect();
        let c = classify(&points).expect("valid");
        assert_eq!(c.knot, KnotType::Unknot, "trial {trial}: {}", show("ascending", &c));
        diagrams += c.votes.len();
        kept_crossings += c.votes.iter().filter(|v| v.crossings > 0).count();
    }
    println!(
        "{kept_crossings} of {diagrams} ascending diagrams kept crossings after reduction; all called unknots"
    );
    assert!(kept_crossings > 0, "the determinant rule was never needed: make the curves harder");
}

/// The trefoil, figure-eight and cinquefoil cut open on their rim get their knot, determinant, writhe and
/// crossing count, and a mirrored trefoil the opposite writhe.
#[test]
fn closed_knots_cut_open_on_their_rim() {
    let trefoil = check("trefoil", &torus_knot(2.0, 3.0, 200), KnotType::Trefoil, 3, 3);
    assert_eq!(trefoil.crossings, 3);
    assert_eq!(trefoil.agreement, 1.0);
    let eight = check("figure-eight", &figure_eight(200), KnotType::FigureEight, 5, 0);
    assert_eq!(eight.crossings, 4);
    let cinquefoil = check("cinquefoil", &torus_knot(2.0, 5.0, 250), KnotType::Surgeons, 5, 5);
    assert_eq!(cinquefoil.crossings, 5);
    // Mirror images: same knot, opposite writhe.
    let mirror: Vec<V> = torus_knot(2.0, 3.0, 200).iter().map(|p| V::new(p.x, p.y, -p.z)).collect();
    let mirrored = check("mirror trefoil", &mirror, KnotType::Trefoil, 3, 3);
    assert_eq!(mirrored.writhe, -trefoil.writhe);
}

/// A 6 mm trefoil placed 0.8 m up still classifies as a trefoil with determinant 3 and writhe 3, and so
/// does a trefoil at any scale a float holds, 1e-200 to 1e200 (at 1e160 the projections' products
/// overflowed and it read as the unknot; at 1e-200 they underflowed).
#[test]
fn scale_and_position_do_not_matter() {
    // A 6 mm trefoil tied 0.8 m above the floor.
    let offset = V::new(0.3, -0.2, 0.8);
    let small: Vec<V> = torus_knot(2.0, 3.0, 200).iter().map(|p| offset + p * 0.001).collect();
    check("mm trefoil", &small, KnotType::Trefoil, 3, 3);
    let unit = check("unit trefoil", &torus_knot(2.0, 3.0, 200), KnotType::Trefoil, 3, 3);
    for scale in [1e-200, 1e-100, 1e-3, 1e3, 1e100, 1e160, 1e200] {
        let scaled: Vec<V> = torus_knot(2.0, 3.0, 200).iter().map(|p| p * scale).collect();
        let c = check(&format!("trefoil at {scale:e}"), &scaled, KnotType::Trefoil, 3, 3);
        assert_eq!((c.writhe, c.crossings), (unit.writhe, unit.crossings), "at {scale:e}");
    }
}

/// An open overhand, an overhand in a loop and a suture's single throw each classify as a trefoil.
#[test]
fn open_overhand_closed_far_away_is_a_trefoil() {
    check("open overhand", &open_overhand(), KnotType::Trefoil, 3, 3);
    check(
        "overhand in a loop",
        &loop_with_knots(&[(0.0, hairpin_overhand(false, 90))]),
        KnotType::Trefoil,
        3,
        3,
    );
    // The single throw of a suture, the bite part of the thread.
    check("single throw", &suture(&[3]), KnotType::Trefoil, 3, 3);
}

/// Square knots (opposite throws) and granny knots (like throws), in a loop or as sutures, are told apart by
/// their writhe.
#[test]
fn square_and_granny() {
    let square = loop_with_knots(&[(-1.0, hairpin_overhand(false, 90)), (1.0, hairpin_overhand(true, 90))]);
    check("square (loop)", &square, KnotType::Square, 9, 0);
    let granny = loop_with_knots(&[(-1.0, hairpin_overhand(false, 90)), (1.0, hairpin_overhand(false, 90))]);
    check("granny (loop)", &granny, KnotType::Granny, 9, 6);
    let c = check("square (suture)", &suture(&[3, -3]), KnotType::Square, 9, 0);
    assert_eq!(c.crossings, 6);
    check("granny (suture)", &suture(&[3, 3]), KnotType::Granny, 9, 6);
    check("granny (suture, other hand)", &suture(&[-3, -3]), KnotType::Granny, 9, 6);
}

/// A surgeon's double throw classifies as `surgeons`, unlike a single throw, and a double throw followed by
/// an opposite single throw as the surgeon's knot.
#[test]
fn surgeons_double_throw_and_surgeons_knot() {
    let double = check("double throw", &suture(&[5]), KnotType::Surgeons, 5, 5);
    assert_eq!(double.crossings, 5);
    let single = classify(&suture(&[3])).expect("valid");
    assert_ne!(single.knot, double.knot);
    check("surgeon's knot", &suture(&[5, -3]), KnotType::SurgeonsKnot, 15, 2);
}

/// Every point moved by up to a quarter of the mean segment length, 1000 seeded draws per curve.
#[test]
fn small_perturbations_change_no_verdict() {
    let curves: Vec<(&str, Vec<V>)> = vec![
        ("trefoil", torus_knot(2.0, 3.0, 200)),
        ("figure-eight", figure_eight(200)),
        ("square", suture(&[3, -3])),
        ("granny", suture(&[3, 3])),
        ("double throw", suture(&[5])),
        ("open overhand", open_overhand()),
        ("kinked unknot", kinked_circle(400)),
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for (name, points) in curves {
        let want = classify(&points).expect("valid").knot;
        let mean_segment: f64 =
            points.windows(2).map(|w| (w[1] - w[0]).norm()).sum::<f64>() / (points.len() - 1) as f64;
        let sigma = 0.25 * mean_segment;
        let mut same = 0;
        for _ in 0..1000 {
            let moved: Vec<V> =
                points.iter().map(|p| p + V::from_fn(|_, _| rng.random_range(-sigma..sigma))).collect();
            same += usize::from(classify(&moved).expect("valid").knot == want);
        }
        let rate = same as f64 / 1000.0;
        println!("{name}: {want} kept in {:.1} % of 1000 perturbations of up to {sigma:.3}", rate * 100.0);
        assert!(rate >= 0.99, "{name}: only {:.1} % kept {want}", rate * 100.0);
    }
}

/// A centreline with too few points, a repeated point or a NaN coordinate is refused, naming the point.
#[test]
fn degenerate_centrelines_are_refused() {
    let points = torus_knot(2.0, 3.0, 50);
    assert_eq!(classify(&points[..3]), Err(KnotError::TooFewPoints { count: 3 }));
    let mut repeated = points.clone();
    repeated[10] = repeated[9];
    assert_eq!(classify(&repeated), Err(KnotError::DuplicatePoint { index: 10, previous: 9 }));
    let mut nan = points.clone();
    nan[7].x = f64::NAN;
    let error = classify(&nan).expect_err("NaN refused");
    assert!(matches!(error, KnotError::NotFinite { index: 7, axis: 'x', .. }), "{error}");
    assert_eq!(error.to_string(), "point 7: x is not finite (NaN)");
}

/// A valid CSV centreline reads back as its trefoil, and a short, duplicated, NaN, malformed or missing file
/// is refused with a message naming the file and, where it has one, the bad line.
#[test]
fn csv_files_name_the_bad_line() {
    let dir = std::env::temp_dir().join(format!("knotlab-knot-csv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).expect("write csv");
        path
    };
    let good: String = std::iter::once("x,y,z\n".to_owned())
        .chain(torus_knot(2.0, 3.0, 100).iter().map(|p| format!("{},{},{}\n\n", p.x, p.y, p.z)))
        .collect();
    let points = read_points(&write("good.csv", &good)).expect("valid file");
    assert_eq!(classify(&points).expect("valid").knot, KnotType::Trefoil);
    let cases = [
        ("short.csv", "x,y,z\n0,0,0\n1,0,0\n1,1,0\n", "short.csv: line 4: end of file after only 3 point(s)"),
        ("dup.csv", "0,0,0\n1,0,0\n1,0,0\n2,1,0\n", "dup.csv: line 3: repeats the point on line 2"),
        ("nan.csv", "0,0,0\n1,0,0\n1,nan,0\n2,1,0\n", "nan.csv: line 3: y = 'nan' is not finite"),
        (
            "bad.csv",
            "x,y,z\n0,0,0\n1;0;0\n",
            "bad.csv: line 3: expected 3 comma-separated numbers x,y,z, found 1",
        ),
    ];
    for (name, text, message) in cases {
        let error = read_points(&write(name, text)).expect_err("refused").to_string();
        assert!(error.contains(message), "{error}");
    }
    let missing = read_points(&dir.join("missing.csv")).expect_err("no file").to_string();
    assert!(missing.contains("missing.csv: cannot read"), "{missing}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A throw tied at the stitch is judged a success; the wrong knot type, a knot 10 mm from the tissue, or no
/// knot each fail with their own mode.
#[test]
fn verdicts_from_topology_and_tightness() {
    // A single throw tied 1 mm above a tissue surface, its stitch at the knot.
    let scale = 0.001;
    let points: Vec<V> = suture(&[3]).iter().map(|p| p * scale).collect();
    let knotted = classify(&points).expect("valid");
    let span = knotted.span.clone().expect("a knot has a span");
    assert!(span.start_m > 0.0 && span.end_m < span.thread_length_m && span.length_m() > 0.0);
    // The twist sits at y in [-0.5, 0.5] mm: the tissue is the plane y = -1.5 mm, normal +y.
    let surface = TissueSurface::new(V::new(0.0, -0.0015, 0.0), V::y()).expect("normal");
    let site = StitchSite { surface, stitch_m: V::new(0.0, -0.0015, 0.0) };
    let limits = DownLimits::default();
    assert_eq!(judge(&knotted, &[KnotType::Trefoil], &site, &limits), Verdict::Success);
    assert_eq!(
        judge(&knotted, &[KnotType::Square], &site, &limits),
        Verdict::Failure(FailureMode::WrongKnotType)
    );
    let far = StitchSite {
        surface: TissueSurface::new(V::new(0.0, -0.01, 0.0), V::y()).expect("normal"),
        stitch_m: V::new(0.0, -0.01, 0.0),
    };
    assert_eq!(
        judge(&knotted, &[KnotType::Trefoil], &far, &limits),
        Verdict::Failure(FailureMode::KnotNotDown)
    );
    let loose = classify(&kinked_circle(200)).expect("valid");
    assert_eq!(judge(&loose, &[KnotType::Trefoil], &site, &limits), Verdict::Failure(FailureMode::NoKnot));
}

/// Work and memory stay bounded on any centreline (a 100,000-point helix asked for 10 GB, 10,000
/// random-walk points did not finish in two minutes): a 10,000-point random walk is classified with
/// every picture searched; a coil whose pictures along its axis hold more crossings than
/// `MAX_CROSSINGS` votes `unknown` there, unsearched, instead of growing without bound, and so does
/// the 100,000-point helix; more points than `MAX_POINTS` are refused before anything is built.
#[test]
fn tangled_and_huge_centrelines_take_bounded_work() {
    use knotlab_sim::knot::centreline::MAX_POINTS;
    use knotlab_sim::knot::crossings::MAX_CROSSINGS;
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut walk = vec![V::zeros()];
    for _ in 1..10_000 {
        let last = walk[walk.len() - 1];
        walk.push(last + V::from_fn(|_, _| rng.random_range(-1e-3..1e-3)));
    }
    let c = classify(&walk).expect("a walk classifies");
    assert!(c.votes.iter().all(|v| v.searched), "{:?}", c.votes);
    assert!(c.votes.iter().map(|v| v.raw_crossings).sum::<usize>() > 10_000, "the walk crosses itself");
    // 600 turns of 10 points, the radius wobbling so that turns cross along the axis: about 360,000
    // crossings there.
    let coil: Vec<V> = (0..6000)
        .map(|k| {
            let t = TAU * k as f64 / 10.0;
            let r = 0.01 * (1.0 + 0.2 * (0.37 * k as f64).sin());
            V::new(r * t.cos(), r * t.sin(), 1e-6 * k as f64)
        })
        .collect();
    let c = classify(&coil).expect("a coil classifies");
    let unsearched: Vec<&knotlab_sim::knot::DirectionVote> = c.votes.iter().filter(|v| !v.searched).collect();
    assert!(!unsearched.is_empty(), "{:?}", c.votes);
    for v in unsearched {
        assert_eq!((v.knot, v.determinant), (KnotType::Unknown, None));
        assert!(v.raw_crossings > MAX_CROSSINGS, "{v:?}");
    }
    // The helix that asked for 10 GB: 100,000 points, 1,000 turns, its pictures along the axis
    // crossing about a million times.
    let helix: Vec<V> = (0..100_000)
        .map(|k| {
            let t = TAU * k as f64 / 100.0;
            V::new(0.01 * t.cos(), 0.01 * t.sin(), 1e-6 * k as f64)
        })
        .collect();
    let c = classify(&helix).expect("the helix classifies");
    assert!(c.votes.iter().any(|v| !v.searched), "{:?}", c.votes);
    assert!(matches!(c.knot, KnotType::Unknot | KnotType::Unknown), "{:?}", c.knot);
    let many = vec![V::zeros(); MAX_POINTS + 1];
    assert_eq!(classify(&many), Err(KnotError::TooManyPoints { count: MAX_POINTS + 1, max: MAX_POINTS }));
}
