//! Issue 47: `tribofe rupture --scene FILE.toml`, general 2D in-plane rupture scenes: the
//! flag-driven scene reproduced bit for bit from a file, the refusals of a bad file, station
//! output against the run's own fields, and TPV205-2D at h = 200 m against its committed values.

use std::path::{Path, PathBuf};
use std::process::Command;
use tribofe::dynamics::rupture::{self, RuptureSpec, SceneSpec};
use tribofe::law::Normal;
use tribofe::scene::Scene;

fn tribofe(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_tribofe")).args(args).output().expect("tribofe runs")
}

fn tpv205() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("validation/dynamics/tpv205_2d/tpv205_2d.toml")
}

/// The flag-driven default scene as a file: every value the flags set, the patch's shear as
/// the flags compute it (printed to round-trip exactly).
fn default_scene_text() -> String {
    let d = RuptureSpec::default();
    format!(
        "[block]\nlength = {:?}\nthickness = {:?}\nyoung = {:?}\npoisson = {:?}\ndensity = {:?}\n\
         [mesh]\nh = {:?}\n\
         [law]\nkind = \"slip-weakening\"\nmu_s = {:?}\nmu_d = {:?}\ndc = {:?}\n\
         [interface]\nkind = \"bilateral\"\nsigma0 = {:?}\ns = {:?}\n\
         [interface.nucleation]\nx_min = {:?}\nx_max = {:?}\ntau0 = {:?}\n\
         [rupture]\nt_end = {:?}\nreflections = \"allowed\"\nspeed_window = [{:?}, {:?}]\n",
        d.length,
        d.height,
        d.young,
        d.poisson,
        d.density,
        d.h,
        d.friction.mu_s(),
        d.friction.mu_d(),
        d.dc(),
        d.sigma0,
        d.s_ratio,
        -d.patch_half_width,
        d.patch_half_width,
        d.overstress * d.friction.mu_s() * d.sigma0,
        d.t_end,
        d.speed_window.0,
        d.speed_window.1
    )
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn a_scene_file_reproduces_the_flag_driven_run_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "default.toml", &default_scene_text());
    // In the library: the scene's spec runs to the same bits as the flags' defaults.
    let from_file = SceneSpec::from_scene(&Scene::from_file(&file).unwrap()).unwrap().spec;
    let flags = RuptureSpec { normal: Normal::Time { t: rupture::DEFAULT_NORMAL_LAG }, ..Default::default() };
    let run = |s: &RuptureSpec| rupture::run(s, &tribofe::Cancel::new(), tribofe::Progress::none()).unwrap();
    let (a, b) = (run(&from_file), run(&flags));
    assert_eq!(a.tau0, b.tau0);
    assert_eq!(a.t_arrival, b.t_arrival);
    assert_eq!(a.slip, b.slip);
    assert_eq!(a.peak_slip_rate, b.peak_slip_rate);
    assert_eq!(a.force_drop.to_bits(), b.force_drop.to_bits());
    assert_eq!(a.energy, b.energy);
    assert!(a.t_arrival.iter().filter(|t| t.is_some()).count() > 50, "the front ran");
    // And through the command: the same files, byte for byte.
    let (o1, o2) = (dir.path().join("flags"), dir.path().join("scene"));
    for (args, out) in [(vec!["rupture"], &o1), (vec!["rupture", "--scene", file.to_str().unwrap()], &o2)] {
        let r = tribofe(&[&args[..], &["--out", out.to_str().unwrap()]].concat());
        assert!(r.status.success(), "{args:?}: {}", String::from_utf8_lossy(&r.stderr));
    }
    for f in ["arrival.csv", "summary.csv", "energy.csv", "zone.csv", "rupture_time.csv"] {
        assert_eq!(std::fs::read(o1.join(f)).unwrap(), std::fs::read(o2.join(f)).unwrap(), "{f}");
    }
    // A flag given overrides the file's key: twice the nodes ruptured at half the h.
    let o3 = dir.path().join("h05");
    let r = tribofe(&[
        "rupture",
        "--scene",
        file.to_str().unwrap(),
        "--h",
        "0.0005",
        "--out",
        o3.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let rows = std::fs::read_to_string(o3.join("rupture_time.csv")).unwrap().lines().count();
    let rows1 = std::fs::read_to_string(o1.join("rupture_time.csv")).unwrap().lines().count();
    assert!(rows > rows1 * 3 / 2, "--h 0.0005 doubles the nodes: {rows} rows against {rows1}");
}

/// The last stderr line of a refused run (status 2, nothing written), which must hold `words`.
fn refused(text: &str, extra: &[&str], words: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "s.toml", text);
    let out = dir.path().join("out");
    let r = tribofe(
        &[&["rupture", "--scene", file.to_str().unwrap(), "--out", out.to_str().unwrap()][..], extra]
            .concat(),
    );
    let err = String::from_utf8_lossy(&r.stderr);
    let last = err.lines().last().unwrap_or("");
    assert_eq!(r.status.code(), Some(2), "{text}\n{err}");
    for w in words {
        assert!(last.contains(w), "no '{w}' in: {last}");
    }
    assert!(!out.exists(), "wrote its --out");
}

#[test]
fn a_bad_scene_is_refused_before_any_work_naming_the_key() {
    let tpv = std::fs::read_to_string(tpv205()).unwrap();
    let with = |from: &str, to: &str| {
        assert!(tpv.contains(from), "{from}");
        tpv.replacen(from, to, 1)
    };
    // An unknown key, named with its line.
    refused(&with("rate_threshold = 1e-3", "rate_treshold = 1e-3"), &[], &["rate_treshold", "line"]);
    // Overlapping intervals setting the same value.
    refused(
        &with("x_min = 6000.0", "x_min = -7000.0"),
        &[],
        &["intervals[1] and intervals[2]", "overlap", "tau0"],
    );
    // A value with neither a background nor intervals covering the block.
    refused(&with("sigma0 = 120e6        # Pa, compression", ""), &[], &["[interface] sigma0", "uncovered"]);
    refused(&with("mu_s = 10000.0", "# no mu_s"), &[], &["[law] mu_s", "uncovered", "-43000 < x < -15000"]);
    // A patch outside the block, a patch below the strength.
    refused(
        &with("x_max = 1500.0", "x_max = 50000.0"),
        &[],
        &["[interface.nucleation] x_min, x_max", "inside the block"],
    );
    refused(
        &with("tau0 = 81.6e6", "tau0 = 80.0e6"),
        &[],
        &["[interface.nucleation] tau0", "nothing would start"],
    );
    // A D_c the mesh cannot resolve: named as the file's key, with the value that would do.
    refused(
        &with("dc = 0.40 ", "dc = 0.12 "),
        &["--h", "200"],
        &["[law] dc", "--h", "fewer than 3", "at most 8.277e1"],
    );
    refused(&with("dc = 0.40 ", "dc = 0.08 "), &[], &["[law] dc", "mesh.h", "fewer than 3"]);
    // A block that lets the waves back to the stations before t_end, not said.
    refused(
        &with("thickness = 36200.0", "thickness = 20000.0"),
        &[],
        &["[rupture] reflections", "top", "6.6667 s", "allowed"],
    );
    refused(&with("t_end = 12.0", "t_end = 13.0"), &["--h", "200"], &["[rupture] reflections", "12.0667 s"]);
    // The material twice, a law the scene does not run, a station off the interface.
    refused(&with("c_p = 6000.0", "young = 3e10\nc_p = 6000.0"), &[], &["block.c_p", "twice"]);
    refused(
        &with("kind = \"slip-weakening\"", "kind = \"rate-state\""),
        &[],
        &["[law] kind", "slip-weakening"],
    );
    refused(
        &with("stations = [-12000.0", "stations = [-50000.0"),
        &[],
        &["[rupture] stations[0]", "off the interface"],
    );
    // The tables of a rupture scene are refused by the other commands.
    let dir = tempfile::tempdir().unwrap();
    let r = tribofe(&[
        "check",
        "--scene",
        tpv205().to_str().unwrap(),
        "--out",
        dir.path().join("o").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(err.contains("[interface]") && err.contains("rupture --scene"), "{err}");
}

/// TPV205-2D at 200 m, the stations against the run's own fields: the shear on a sliding,
/// weakened node is mu_d sigma0 to round-off, the normal stress -sigma0 exactly (a symmetric
/// fault's normal stress does not change), a station between two nodes their mean, the
/// station's rate crossing the threshold within a step of rupture_time, its slip at the end
/// within one step's increment of the run's slip.
#[test]
fn stations_agree_with_the_runs_own_fields() {
    let scene = Scene::from_file(&tpv205()).unwrap();
    let mut spec = SceneSpec::from_scene(&scene).unwrap().spec;
    spec.h = 200.0;
    spec.t_end = 6.0;
    spec.dt_out = None;
    // Nodes at h = 200 m lie at multiples of 200 m: 4500 m is halfway between two.
    spec.stations = vec![0.0, 4400.0, 4500.0, 4600.0];
    let r = rupture::run(&spec, &tribofe::Cancel::new(), tribofe::Progress::none()).unwrap();
    assert_eq!(r.stations.len(), 4);
    let (sigma0, mu_d) = (120e6, 0.525);
    let mut sliding = 0;
    for (j, st) in r.stations.iter().enumerate() {
        for k in 0..st.t.len() {
            assert!((st.normal[k] + sigma0).abs() <= 1e-12 * sigma0, "x = {}, t = {}", st.x, st.t[k]);
            // At the nodes (not 4500 m, between a weakened node and one still weakening).
            if j != 2 && st.slip[k] > 0.4 && st.slip_rate[k] > 0.1 {
                assert!(
                    (st.shear[k] - mu_d * sigma0).abs() <= 1e-9 * sigma0,
                    "t = {}: {}",
                    st.t[k],
                    st.shear[k]
                );
                sliding += 1;
            }
        }
    }
    assert!(sliding > 300, "sliding samples: {sliding}");
    let (a, m, b) = (&r.stations[1], &r.stations[2], &r.stations[3]);
    for k in 0..m.t.len() {
        for (u, v, w) in [(a.slip[k], m.slip[k], b.slip[k]), (a.slip_rate[k], m.slip_rate[k], b.slip_rate[k])]
        {
            assert!((v - 0.5 * (u + w)).abs() <= 1e-9 * (1.0 + u.abs() + w.abs()), "t = {}", m.t[k]);
        }
    }
    // At the nodes: the rate crossing the threshold (1 mm/s) within a step of rupture_time,
    // and the slip at the last record (t_end) the run's slip (its path length: the same while
    // the slip does not reverse).
    let dt = r.dt;
    for st in [&r.stations[0], a, b] {
        let i = r.x.iter().position(|&xi| (xi - st.x).abs() < 1e-6).unwrap();
        let k = st.slip_rate.iter().position(|&v| v > r.rate_threshold).unwrap();
        let t_node = r.rupture_time[i].unwrap();
        assert!((st.t[k] - t_node).abs() <= dt, "x = {}: {} against {t_node}", st.x, st.t[k]);
        let last = st.slip.len() - 1;
        assert_eq!(st.t[last], r.steps as f64 * dt);
        assert!(
            (r.slip[i] - st.slip[last]).abs() <= 1e-9 * r.slip[i],
            "x = {}: {} against {}",
            st.x,
            st.slip[last],
            r.slip[i]
        );
    }
}

/// TPV205-2D at h = 200 m as a regression test: rupture times (the first slip rate above
/// 1 mm/s) and slip at 12 s per station against the committed run
/// (validation/dynamics/tpv205_2d/h200). The run is deterministic (threads or not), so the
/// tolerance is round-off.
#[test]
fn tpv205_2d_at_200_m_matches_its_committed_values() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let r = tribofe(&[
        "rupture",
        "--scene",
        tpv205().to_str().unwrap(),
        "--h",
        "200",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("validation/dynamics/tpv205_2d/h200");
    let read = |p: PathBuf| -> Vec<Vec<f64>> {
        std::fs::read_to_string(&p)
            .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect()
    };
    for x in ["-12000", "-7500", "-4500", "0", "4500", "7500", "12000"] {
        let f = format!("station_x{x}.csv");
        let (new, old) = (read(out.join(&f)), read(committed.join(&f)));
        assert_eq!(new.len(), old.len(), "{f}");
        for (a, b) in new.iter().zip(&old) {
            for (u, v) in a.iter().zip(b) {
                assert!((u - v).abs() <= 1e-9 * (1.0 + v.abs()), "{f}: {a:?} against {b:?}");
            }
        }
    }
    let (new, old) = (read(out.join("rupture_time.csv")), read(committed.join("rupture_time.csv")));
    assert_eq!(new, old);
}
