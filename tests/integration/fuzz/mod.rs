//! Property-based fuzzing of every file and packet parser (proptest, a fixed seed): mutations of a
//! valid shipped input (special numbers, arrays of another length, truncation, repeated or deleted
//! lines, values of another type, deep nesting) and raw random bytes. Each case must return `Ok` or
//! an `Err` whose message is not empty: never panic, never abort, never hang.
//!
//! `KNOTLAB_FUZZ_CASES` sets the cases per strategy (default [`DEFAULT_CASES`]; the folder loader
//! and the knot classifier run a tenth of it, the packet decoder four times it and the knot CSV
//! parser twice), `KNOTLAB_FUZZ_SEED` another seed (default 0). Each
//! test runs in a child process under a bound on its address space, `KNOTLAB_FUZZ_MEMORY_MIB`
//! (default [`DEFAULT_MEMORY_MIB`], 0 for none), so that an allocation out of bound, like a stack
//! overflow, fails that test alone. Each test prints the cases it tried, how many parsed, its
//! slowest case and its peak memory. A long run keeps the same 1 GiB bound (the test binary itself
//! needs about 160 MiB of it):
//!
//! ```text
//! KNOTLAB_FUZZ_CASES=1000000 KNOTLAB_FUZZ_MEMORY_MIB=1024 cargo test --release --test integration fuzz:: -- --nocapture
//! ```

mod demonstration;
mod field_buses;
mod fluid_path;
mod knot_csv;
mod knowledge_base;
mod melfa;
mod mutate;
mod toml_files;
mod urdf;

use std::fmt::Debug;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

use proptest::strategy::Strategy;
use proptest::test_runner::{Config, RngAlgorithm, RngSeed, TestCaseError, TestRng, TestRunner};

/// Cases per strategy when `KNOTLAB_FUZZ_CASES` is not set.
pub const DEFAULT_CASES: u32 = 700;

/// A case slower than this fails: a parser must not take seconds over an input of a few hundred
/// kilobytes (a machine shared with other work stays far below it).
const SLOWEST_CASE: Duration = Duration::from_secs(20);

/// How much of the slowest case's value a test prints.
const SHOWN_CHARS: usize = 240;

/// The cases per strategy: `KNOTLAB_FUZZ_CASES`, or [`DEFAULT_CASES`].
pub fn cases() -> u32 {
    match std::env::var("KNOTLAB_FUZZ_CASES") {
        Ok(text) => {
            text.trim().parse().unwrap_or_else(|_| panic!("KNOTLAB_FUZZ_CASES={text:?} is not a count"))
        }
        Err(_) => DEFAULT_CASES,
    }
}

/// `KNOTLAB_FUZZ_SEED`, or 0.
fn seed() -> u64 {
    match std::env::var("KNOTLAB_FUZZ_SEED") {
        Ok(text) => text.trim().parse().unwrap_or_else(|_| panic!("KNOTLAB_FUZZ_SEED={text:?} is not a u64")),
        Err(_) => 0,
    }
}

/// A shipped file's text (`path` from the repository's root).
pub fn shipped(path: &str) -> String {
    let full = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("{}: {e}", full.display()))
}

/// What a parser said about one input: `Ok`, or its error's message.
pub type Outcome = Result<(), String>;

/// The outcome of a parser's result.
pub fn outcome<T, E: std::fmt::Display>(result: Result<T, E>) -> Outcome {
    result.map(|_| ()).map_err(|e| e.to_string())
}

/// Runs `check` on `cases` values of `strategy` with a seed fixed by `name` (no failure
/// persisted to disk). A case fails when `check` panics, when the parser's error message is empty,
/// or when it takes longer than [`SLOWEST_CASE`]; the test then fails on the smallest failing value
/// proptest finds. Prints the cases tried, how many parsed, and the slowest case (its value's
/// beginning: the mutations come first).
pub fn fuzz<S>(name: &str, cases: u32, strategy: S, check: impl Fn(&S::Value) -> Outcome)
where
    S: Strategy,
    S::Value: Debug,
{
    let config = Config {
        cases: cases.max(1),
        failure_persistence: None,
        rng_algorithm: RngAlgorithm::ChaCha,
        rng_seed: RngSeed::Fixed(seed()),
        max_shrink_iters: 2048,
        max_shrink_time: 120_000,
        ..Config::default()
    };
    // A 32-byte ChaCha seed from the test's name and KNOTLAB_FUZZ_SEED: every test draws its own
    // sequence, the same one every run.
    let mut bytes = [0u8; 32];
    for (k, chunk) in bytes.chunks_mut(8).enumerate() {
        let mut h = 0xcbf2_9ce4_8422_2325_u64 ^ seed().rotate_left(16 * k as u32) ^ k as u64;
        for b in name.bytes() {
            h = (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
        chunk.copy_from_slice(&h.to_le_bytes());
    }
    let mut runner = TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &bytes));
    let (tried, parsed, slowest_ns) = (AtomicU64::new(0), AtomicU64::new(0), AtomicU64::new(0));
    let slowest_case = Mutex::new(String::new());
    let start = Instant::now();
    let result = runner.run(&strategy, |value| {
        let t = Instant::now();
        let said = check(&value);
        let took = t.elapsed();
        tried.fetch_add(1, Ordering::Relaxed);
        if slowest_ns.fetch_max(took.as_nanos() as u64, Ordering::Relaxed) < took.as_nanos() as u64 {
            let case: String = format!("{value:?}").chars().take(SHOWN_CHARS).collect();
            *slowest_case.lock().unwrap_or_else(PoisonError::into_inner) = case;
        }
        match said {
            Ok(()) => {
                parsed.fetch_add(1, Ordering::Relaxed);
            }
            Err(message) if message.trim().is_empty() => {
                return Err(TestCaseError::fail("the error's message is empty"));
            }
            Err(_) => {}
        }
        if took > SLOWEST_CASE {
            return Err(TestCaseError::fail(format!("took {took:.1?} (more than {SLOWEST_CASE:?})")));
        }
        Ok(())
    });
    eprintln!(
        "fuzz {name}: {} cases tried ({} parsed), {:.1?} in all, slowest {:.1?}: {}",
        tried.load(Ordering::Relaxed),
        parsed.load(Ordering::Relaxed),
        start.elapsed(),
        Duration::from_nanos(slowest_ns.load(Ordering::Relaxed)),
        slowest_case.into_inner().unwrap_or_else(PoisonError::into_inner),
    );
    if let Err(e) = result {
        panic!("fuzz {name}: {e}");
    }
}

/// The environment variable that marks the child process [`isolated`] runs a test in.
const CHILD: &str = "KNOTLAB_FUZZ_CHILD";

/// The address space a fuzz test's process may use, MiB, when `KNOTLAB_FUZZ_MEMORY_MIB` is not set:
/// the test binary's own (about 160 MiB with its libraries and threads) and over 800 MiB for the
/// parsers, whose inputs are at most a few hundred kilobytes.
pub const DEFAULT_MEMORY_MIB: u64 = 1024;

/// `KNOTLAB_FUZZ_MEMORY_MIB` (0: no bound), or [`DEFAULT_MEMORY_MIB`].
fn memory_mib() -> u64 {
    match std::env::var("KNOTLAB_FUZZ_MEMORY_MIB") {
        Ok(text) => {
            text.trim().parse().unwrap_or_else(|_| panic!("KNOTLAB_FUZZ_MEMORY_MIB={text:?} is not a count"))
        }
        Err(_) => DEFAULT_MEMORY_MIB,
    }
}

/// Runs a fuzz test's `body` in a child process of this test binary that runs that test alone, its
/// address space bounded (`ulimit -v`, [`memory_mib`]): an abort (a stack overflow, an allocation that
/// fails) fails this test, with what the child printed, and not every test of the binary. Runs
/// `body` in this process where the thread does not carry the test's name, or in the child.
pub fn isolated(body: impl FnOnce()) {
    let thread = std::thread::current();
    let name = thread.name().filter(|n| n.starts_with("fuzz::"));
    let (Some(name), None, true) = (name, std::env::var_os(CHILD), cfg!(unix)) else {
        body();
        report_memory();
        return;
    };
    let exe = std::env::current_exe().expect("the test binary");
    let mib = memory_mib();
    let bound = if mib == 0 { "none".to_owned() } else { format!("{mib} MiB") };
    let mut command = if mib == 0 {
        std::process::Command::new(&exe)
    } else {
        let mut sh = std::process::Command::new("sh");
        sh.args(["-c", "ulimit -v \"$1\" && shift && exec \"$@\"", "sh", &(mib * 1024).to_string()])
            .arg(&exe);
        sh
    };
    let started = Instant::now();
    let out = command
        .args([name, "--exact", "--nocapture", "--test-threads=1"])
        .env(CHILD, "1")
        .output()
        .expect("run the test in a child process");
    let stderr = String::from_utf8_lossy(&out.stderr);
    eprint!("{stderr}");
    eprintln!("fuzz {name}: {:.1?} in a child process (address space bound: {bound})", started.elapsed());
    assert!(
        out.status.success(),
        "{name}: the child process failed ({}; address space bound: {bound}):\n{}",
        out.status,
        stderr.lines().rev().take(12).collect::<Vec<_>>().into_iter().rev().collect::<Vec<_>>().join("\n"),
    );
}

/// Prints the process's peak address space and resident memory (Linux), after a test's cases.
fn report_memory() {
    let Ok(status) = std::fs::read_to_string("/proc/self/status") else { return };
    let field = |key: &str| {
        status.lines().find_map(|l| l.strip_prefix(key)).map_or("?".to_owned(), |v| v.trim().to_owned())
    };
    let thread = std::thread::current();
    eprintln!(
        "fuzz {}: peak address space {}, peak resident {}",
        thread.name().unwrap_or("test"),
        field("VmPeak:"),
        field("VmHWM:")
    );
}

/// A directory under the system's temp dir, removed when dropped.
pub struct TempDir(pub PathBuf);

impl TempDir {
    /// A fresh, empty directory named after `name` and this process.
    pub fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("knotlab-fuzz-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(&dir).expect("temp dir");
        Self(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}
