//! What the emulator commands share: `--duration-s` checked, and serving until it has passed or
//! Ctrl-C is pressed.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// `--duration-s`, when given, must be a positive, finite number of seconds.
pub fn check_duration(duration_s: Option<f64>) -> anyhow::Result<()> {
    if let Some(t) = duration_s
        && !(t.is_finite() && t > 0.0)
    {
        anyhow::bail!("--duration-s: {t} is not a positive, finite number of seconds");
    }
    Ok(())
}

/// Returns after `duration_s` (None: never) or at Ctrl-C, whichever comes first.
pub fn until_stopped(duration_s: Option<f64>) -> anyhow::Result<()> {
    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = Arc::clone(&stop);
        ctrlc::set_handler(move || stop.store(true, Ordering::SeqCst))?;
    }
    let started = Instant::now();
    while !stop.load(Ordering::SeqCst) && duration_s.is_none_or(|t| started.elapsed().as_secs_f64() < t) {
        std::thread::sleep(Duration::from_millis(10));
    }
    Ok(())
}
