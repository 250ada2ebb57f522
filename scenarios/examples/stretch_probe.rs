//! Where the suture is stretched or pinched during one trial of the learned skill, and what holds or
//! touches it there:
//!
//! ```text
//! cargo run --release -p knotlab-scenarios --example stretch_probe -- [TURN_DEG] [METHOD] [RATIO] [SHIFT_X_M SHIFT_Y_M SHIFT_Z_M] [TILT_DEG]
//! ```
//!
//! The nominal scene's stitch turned by TURN_DEG (default 0) about the tissue's normal, shifted by
//! SHIFT_X_M, SHIFT_Y_M, SHIFT_Z_M (world frame, default 0) and tilted by TILT_DEG about the wound
//! (default 0), the skill carried there by METHOD (fluid, dmp or replay; default fluid), seed 0. Whenever the most stretched
//! segment is stretched beyond RATIO (default 0.08) of its rest length it prints (at most every 0.25
//! s): the time, the segment, its neighbours' stretch, the links the particles near it touch, the
//! instruments' force gauges, the grips and the run inside the stitch. At the end: the verdict with
//! the coils at the left's take, the long end's turns round the left's and the right's jaws every 0.5
//! s, and the moments at which a particle touched two instruments at once (the thread pinched between
//! them).
//! A single segment stretched with its neighbours compressed is a particle pushed along the rope by a
//! contact, not tension; tension stretches a run of segments alike.

use knotlab_learner::primitive::learn;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::shipped;
use knotlab_scenarios::trial::{Learned, StitchMove, TrialSetup, run_trial};
use nalgebra::Vector3;

fn number(args: &[String], k: usize, default: f64, what: &str) -> f64 {
    match args.get(k) {
        None => default,
        Some(text) => text.parse().unwrap_or_else(|_| {
            eprintln!("stretch_probe: argument {k} ({what}): {text:?} is not a number");
            std::process::exit(2)
        }),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let rotate_deg = number(&args, 1, 0.0, "TURN_DEG");
    let method = match args.get(2).map_or("fluid", String::as_str) {
        "fluid" => Method::Fluid,
        "dmp" => Method::Dmp,
        "replay" => Method::Replay,
        other => {
            eprintln!("stretch_probe: argument 2 (METHOD): {other:?}: use fluid, dmp or replay");
            std::process::exit(2)
        }
    };
    let threshold = number(&args, 3, 0.08, "RATIO");
    let demonstration = shipped::demonstration(None).expect("demo");
    let task = shipped::pattern(None).expect("pattern");
    let knowledge = learn(&demonstration, &task).expect("learned");
    let learned = Learned { knowledge, demonstration };
    let scene = shipped::scene(None, &shipped::SCENE).expect("scene");
    let setup = TrialSetup {
        scene,
        scene_name: "default".into(),
        seed: 0,
        stitch: StitchMove {
            offset_m: Vector3::new(
                number(&args, 4, 0.0, "SHIFT_X_M"),
                number(&args, 5, 0.0, "SHIFT_Y_M"),
                number(&args, 6, 0.0, "SHIFT_Z_M"),
            ),
            rotate_rad: rotate_deg.to_radians(),
            tilt_rad: number(&args, 7, 0.0, "TILT_DEG").to_radians(),
        },
        method,
        offsets: Vec::new(),
    };
    let mut last_print = -1.0;
    let mut pinched: Vec<(f64, usize)> = Vec::new();
    let mut coils: Vec<(f64, Option<f64>, Option<f64>)> = Vec::new();
    let mut observer = |record: &knotlab_hw::controller::CycleRecord,
                        world: &knotlab_sim::world::SimWorld| {
        let t = record.skill_time_s;
        let suture = world.suture();
        let Some(rope) = suture.as_rope() else { return };
        let x = &rope.ropes.x;
        let sp = rope.spacing_m;
        if record.cycle.is_multiple_of(500) {
            let turns = |arm| knotlab_scenarios::expert::diagnose::long_end_turns_around_jaws(world, arm);
            coils.push((t, turns(knotlab_hw::rig::ArmName::Left), turns(knotlab_hw::rig::ArmName::Right)));
        }
        if record.cycle.is_multiple_of(10) {
            let contacts = world.thread_contacts();
            let mut by: std::collections::BTreeMap<usize, (bool, bool, bool)> = Default::default();
            for (p, name) in &contacts {
                let e = by.entry(*p).or_default();
                e.0 |= name.starts_with("left");
                e.1 |= name.starts_with("right");
                e.2 |= name.starts_with("assist");
            }
            if let Some((p, _)) =
                by.iter().find(|(_, (l, r, a))| usize::from(*l) + usize::from(*r) + usize::from(*a) >= 2)
            {
                pinched.push((t, *p));
            }
        }
        let (worst, ratio) = (0..x.len() - 1)
            .map(|i| (i, (x[i + 1] - x[i]).norm() / sp - 1.0))
            .fold((0, f64::MIN), |a, b| if b.1 > a.1 { b } else { a });
        if ratio > threshold && t - last_print > 0.25 {
            last_print = t;
            let near: Vec<String> = rope
                .contacts
                .attachments
                .iter()
                .filter(|a| a.particle + 4 >= worst && a.particle <= worst + 5)
                .map(|a| format!("{}@{}", suture.body_name(a.body).unwrap_or_default(), a.particle))
                .collect();
            let grips: Vec<String> = rope
                .contacts
                .grips
                .iter()
                .map(|g| {
                    format!(
                        "{}:{:.1}N{}",
                        suture.body_name(g.body).unwrap_or_default(),
                        g.limit_n,
                        if g.sliding { " sliding" } else { "" }
                    )
                })
                .collect();
            let around: Vec<String> = (worst.saturating_sub(3)..(worst + 5).min(x.len() - 1))
                .map(|i| format!("{:.2}", (x[i + 1] - x[i]).norm() / sp - 1.0))
                .collect();
            let touching: Vec<String> = world
                .thread_contacts()
                .into_iter()
                .filter(|(p, _)| *p + 4 >= worst && *p <= worst + 5)
                .map(|(p, name)| format!("{p}:{name}"))
                .collect();
            println!("   touching {touching:?}");
            let gauge = |arm| record.arm(arm).map_or(0.0, |a| a.world_force_n.norm());
            println!(
                "   gauges: left {:.2} N, right {:.2} N, assist {:.2} N",
                gauge(knotlab_hw::rig::ArmName::Left),
                gauge(knotlab_hw::rig::ArmName::Right),
                gauge(knotlab_hw::rig::ArmName::Assist)
            );
            println!(
                "t {t:6.2} s seg {worst:3} stretch {ratio:.3} ({:.1} N at EA 160) around [{}] held {:?} grips {:?} inside {:?}",
                ratio * 160.0,
                around.join(" "),
                near,
                grips,
                suture.inside()
            );
        }
    };
    let options = RecordOptions { cycles_per_sample: 10, ..RecordOptions::default() };
    let run = run_trial(&learned, &setup, &options, Some(&mut observer)).expect("ran");
    println!("{:?} coils at the take {:?}", run.run.evaluation.verdict, run.run.coils_at_take);
    let show = |x: Option<f64>| x.map_or("-".to_owned(), |v| format!("{v:.2}"));
    let line: Vec<String> =
        coils.iter().map(|(t, l, r)| format!("{t:.1}: {}/{}", show(*l), show(*r))).collect();
    println!("the long end's turns round the left's / the right's jaws: {}", line.join(", "));
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for (t, _) in &pinched {
        match spans.last_mut() {
            Some((_, end)) if *t - *end < 0.05 => *end = *t,
            _ => spans.push((*t, *t)),
        }
    }
    println!(
        "a particle touching two instruments in {} of the sampled cycles: {:?}",
        pinched.len(),
        spans.iter().map(|(a, b)| format!("{a:.2}-{b:.2}")).collect::<Vec<_>>()
    );
}
