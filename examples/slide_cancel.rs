//! Driving a slide from another program: a progress callback prints how far the drive is, a
//! watcher thread cancels the first (long) run midway, then a shorter run goes to the end and
//! its states come back as arrays (events x nodes), ready for numpy or a plot.
//!
//! `cargo run --release --example slide_cancel`

use std::sync::atomic::{AtomicU64, Ordering};
use tribofe::law::{Law, Rule};
use tribofe::scene::Scene;
use tribofe::studies::slide::{self, SlideOptions, StateField};
use tribofe::{Cancel, Error, Progress, Tick};

fn main() -> Result<(), Error> {
    let scene = Scene::default();
    let law = Law::static_kinetic(0.648, 0.583, Rule::Paper)?;

    // 1. Ten stick-slip cycles, stopped from another thread once the drive is 20 % done.
    let cancel = Cancel::new();
    let long = SlideOptions { law, cycles: 10, cancel: cancel.clone(), ..Default::default() };
    // The last fraction reported, in per mille, for the watcher to read.
    let done = AtomicU64::new(0);
    let print = |t: &Tick| {
        if let Some(f) = t.fraction {
            let permille = (f * 1000.0) as u64;
            if permille / 100 > done.swap(permille, Ordering::Relaxed) / 100 {
                println!("long run: {:.0} % of the drive", 100.0 * f);
            }
        }
    };
    let outcome = std::thread::scope(|s| {
        s.spawn(|| {
            while done.load(Ordering::Relaxed) < 200 {
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
            cancel.cancel();
        });
        let r = slide::run(&scene, &long, Progress::new(&print));
        cancel.cancel(); // the watcher ends even if the run finished first
        r
    });
    match outcome {
        Err(Error::Interrupted) => {
            println!("long run: cancelled at {} per mille, nothing written", done.load(Ordering::Relaxed))
        }
        Ok(_) => println!("long run: finished before the cancel"),
        Err(e) => return Err(e),
    }

    // 2. One cycle to the end, then the states as arrays.
    let short = SlideOptions { law, cycles: 1, ..Default::default() };
    let r = slide::run(&scene, &short, Progress::none())?;
    let (slip, [events, nodes]) = r.field(StateField::Slip);
    let (code, _) = r.field(StateField::Code);
    let ev = r.event_columns();
    println!("short run: {events} states x {nodes} interface nodes");
    let last = &slip[(events - 1) * nodes..];
    let slipping = code[(events - 1) * nodes..].iter().filter(|&&c| c == 1.0).count();
    println!(
        "last state: largest slip {:.3e} m, {slipping} of {nodes} nodes slipping; last event {} at F/(mu_s N) = {:.4}",
        last.iter().fold(0.0f64, |m, v| m.max(v.abs())),
        ev.kind[ev.kind.len() - 1],
        ev.f_over_mu_s_n[ev.kind.len() - 1]
    );
    Ok(())
}
