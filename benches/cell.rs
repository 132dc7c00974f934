//! One benchmark cell per process, following the protocol of WORKLOADS.md; driven by
//! `bench/compare.py`. Usage (after `cargo build --release --benches`):
//!
//! (`<host>` is the host triple, e.g. `x86_64-unknown-linux-gnu`; see `.cargo/config.toml`)
//!
//! ```text
//! target/<host>/release/deps/cell-<hash> W2 20
//! target/<host>/release/deps/cell-<hash> W3.chain 6
//! target/<host>/release/deps/cell-<hash> W1 1 | W1.check 1 | W4 1000
//! target/<host>/release/deps/cell-<hash> W4.trace      (diagnostic: the slow W4 pairs)
//! ```
//!
//! Prints `{"event":"start"}` / `{"event":"end"}` heartbeats around each run (so the
//! driver can kill a run longer than 60 s) and finally one JSON record.

mod common;

use common::*;
use serde_json::{json, Value};
use std::io::Write;
use std::time::{Duration, Instant};

fn beat(ev: &str, t: Option<f64>) {
    let mut o = std::io::stdout().lock();
    match t {
        Some(t) => writeln!(o, "{{\"event\":\"{ev}\",\"t\":{t}}}").unwrap(),
        None => writeln!(o, "{{\"event\":\"{ev}\"}}").unwrap(),
    }
    o.flush().unwrap();
}

type Cell = Box<dyn FnMut() -> (f64, Value)>;

/// Builds the input of a cell (untimed) and returns a closure running the timed region
/// once, which returns (seconds, fingerprint); the fingerprint is computed untimed.
fn cell(workload: &str, size: usize) -> Cell {
    match workload {
        "W1" => {
            let w = w1_prepare();
            Box::new(move || {
                let t = Instant::now();
                let r = w1_run(&w);
                let dt = t.elapsed().as_secs_f64();
                (dt, w1_fingerprint(&r))
            })
        }
        "W1.check" => Box::new(move || {
            let t = Instant::now();
            let r = w1check_run();
            let dt = t.elapsed().as_secs_f64();
            (dt, w1check_fingerprint(&r))
        }),
        "W2" => {
            let p = w2_prepare(size as u32);
            Box::new(move || {
                let t = Instant::now();
                let r = w2_run(&p);
                let dt = t.elapsed().as_secs_f64();
                (dt, w2_fingerprint(&r))
            })
        }
        w if w.starts_with("W3.") => {
            let kind = w[3..].to_string();
            let p = w3_prepare(&kind, size);
            Box::new(move || {
                let t = Instant::now();
                let r = w3_run(&p);
                let dt = t.elapsed().as_secs_f64();
                (dt, w3_fingerprint(&kind, &r))
            })
        }
        "W4" => {
            let mut w = w4_prepare();
            w.pairs.truncate(size);
            Box::new(move || {
                let t = Instant::now();
                let r = w4_run(&w);
                let dt = t.elapsed().as_secs_f64();
                (dt, w4_fingerprint(&w, &r))
            })
        }
        _ => panic!("unknown workload {workload}"),
    }
}

/// This process's peak resident set (VmHWM), in kB (Linux; 0 elsewhere).
fn peak_rss_kb() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1).and_then(|v| v.parse().ok()))
        })
        .unwrap_or(0)
}

fn smallest(workload: &str, size: usize) -> usize {
    match workload {
        "W2" => 2,
        w if w.starts_with("W3.") => 2,
        _ => size,
    }
}

/// Diagnostic: every W4 pair taking more than 20 ms, with a 2 s budget per pair.
fn w4_trace() {
    let w = w4_prepare();
    let mut total = 0.0;
    for (i, p) in w.pairs.iter().enumerate() {
        let one = W4 {
            pairs: vec![(p.0, p.1.clone(), p.2.clone())],
        };
        let _deadline = rigor::normal::limits::until(rigor::clock::Deadline::after(
            Duration::from_secs(2),
            rigor::clock::system(),
        ));
        let t = Instant::now();
        let d = std::panic::catch_unwind(|| w4_run(&one)).ok().map(|d| d[0]);
        let dt = t.elapsed().as_secs_f64();
        total += dt;
        if dt > 0.02 {
            println!("{dt:.4}s  pair {}  label {}  decided {:?}", i + 1, p.0, d);
        }
    }
    println!("total {total:.3}s");
}

fn main() {
    // `cargo bench` passes `--bench`; ignore flags.
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    if args.is_empty() {
        eprintln!("usage: cell WORKLOAD SIZE   (W1 1, W1.check 1, W2 n, W3.chain|tri|dense n, W4 pairs, W4.trace)");
        return;
    }
    let workload = args[0].clone();
    // The workloads measure the engine with ten times the command line's term limit
    // (the figure `bench/compare.py` reports when a cell is refused).
    let _limits = rigor::normal::limits::install(rigor::normal::limits::Limits {
        max_terms: 2_000_000,
        ..rigor::normal::limits::Limits::DEFAULT
    });
    if workload == "W4.trace" {
        w4_trace();
        return;
    }
    let size: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1);
    // Warm-up: the series' smallest size once, untimed.
    {
        let mut c = cell(&workload, smallest(&workload, size));
        let _ = c();
    }
    let mut c = cell(&workload, size);
    beat("start", None);
    let (t0, fp) = c();
    beat("end", Some(t0));
    let mut samples = Vec::new();
    let runs = if t0 < 5.0 {
        ((20.0 / t0).floor() as usize).clamp(3, 7)
    } else {
        samples.push(t0);
        if t0 < 15.0 {
            2
        } else if t0 < 30.0 {
            1
        } else {
            0
        }
    };
    for _ in 0..runs {
        beat("start", None);
        let (t, f) = c();
        beat("end", Some(t));
        samples.push(t);
        assert_eq!(fp, f, "fingerprint changed between runs");
    }
    let mut s = samples.clone();
    s.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let median = if s.len() % 2 == 1 {
        s[s.len() / 2]
    } else {
        (s[s.len() / 2 - 1] + s[s.len() / 2]) / 2.0
    };
    let rec = json!({
        "workload": workload, "variant": "rigor", "tool": "rigor", "size": size,
        "status": "ok", "median": median, "best": s[0], "n": s.len(), "samples": samples,
        "fingerprint": fp, "peak_rss_kb": peak_rss_kb(),
    });
    println!("{rec}");
}
