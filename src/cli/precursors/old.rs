//! The earlier flag forms of `tribofe precursors` (`--map`, `--fe`, `--fe --map`, `--fe
//! --thin-layer LIST`, `--fe --heights LIST`, `--fe --dc LIST`, `--bonded-fields`), hidden
//! from --help and translated into the subcommand each one meant, with the refusals they had.

use super::bonded::BondedArgs;
use super::fe::{FeArgs, FeMapArgs};
use super::model::{MapArgs, ModelArgs};
use super::series::{DcArgs, HeightsArgs, ThinLayerArgs};
use super::{Mode, OutArgs, RgArgs, MAX_DEFAULT_EVENTS};
use std::path::PathBuf;
use tribofe::Error;

#[derive(clap::Args, Debug)]
pub struct Old {
    #[arg(long, default_value_t = tribofe::precursors::PAPER_R)]
    r: f64,
    #[arg(long, default_value_t = tribofe::precursors::PAPER_G)]
    g: f64,
    #[arg(long, default_value = "out/precursors")]
    out: PathBuf,
    #[arg(long)]
    force: bool,
    #[arg(long)]
    events: Option<usize>,
    #[arg(long, conflicts_with_all = ["r", "g", "events"])]
    map: bool,
    #[arg(long)]
    fe: bool,
    #[arg(long, requires = "fe", conflicts_with = "map")]
    cycles: Option<usize>,
    #[arg(long, value_delimiter = ',', requires = "fe", conflicts_with_all = ["map", "cycles"])]
    thin_layer: Option<Vec<f64>>,
    #[arg(long, value_delimiter = ',', requires = "fe", conflicts_with_all = ["map", "cycles", "thin_layer"])]
    heights: Option<Vec<f64>>,
    #[arg(long, value_delimiter = ',', requires = "fe", conflicts_with_all = ["map", "cycles", "thin_layer", "heights"])]
    dc: Option<Vec<f64>>,
    #[arg(long, value_delimiter = ',', default_value = "paper", requires = "fe")]
    rules: Vec<tribofe::law::Rule>,
    #[arg(long, default_value_t = 2000, requires = "fe")]
    max_events: usize,
    #[arg(long, conflicts_with_all = ["map", "fe"])]
    bonded_fields: bool,
    #[arg(long, requires = "bonded_fields")]
    sweep: bool,
    #[command(flatten)]
    scene: super::super::check::SceneArgs,
    #[arg(long, requires = "map")]
    resolution: Option<usize>,
}

impl Old {
    /// The subcommand these flags meant, or the refusal they had.
    pub fn mode(self) -> tribofe::Result<Mode> {
        let given = super::super::given;
        // The model's iteration and map are dimensionless in r and g: no scene can act on them.
        if !self.fe && !self.bonded_fields && self.scene.any() {
            let flag = super::super::scene_args::FLAG_KEYS
                .iter()
                .map(|(f, _)| *f)
                .chain(["--scene", "--write-scene"])
                .find(|f| self.scene.has(f))
                .unwrap_or("--scene");
            return Err(Error::input(
                flag,
                "cannot act without --fe (or --bonded-fields): the model's precursors depend on r and g only",
            ));
        }
        if self.fe {
            if self.events.is_some() {
                return Err(Error::input(
                    "--events",
                    "cannot act with --fe, whose runs end at whole-interface slips (--cycles); its cap is --max-events",
                ));
            }
            if given("max_events") && !self.map && self.dc.is_none() {
                return Err(Error::input(
                    "--max-events",
                    "cannot act here: it caps --fe --map cells and --fe --dc runs",
                ));
            }
            if self.cycles.is_some() && self.dc.is_some() {
                return Err(Error::input(
                    "--cycles",
                    "cannot act with --dc, whose runs stop after one cycle",
                ));
            }
            if given("rules") && !self.map {
                return Err(Error::input(
                    "--rules",
                    "cannot act without --map: --fe runs every rule for fig. 4",
                ));
            }
        }
        let out = OutArgs { out: self.out, force: self.force };
        let rg = RgArgs { r: self.r, g: self.g };
        let scene = self.scene;
        Ok(match (self.fe, self.map) {
            (true, true) => Mode::FeMap(FeMapArgs {
                resolution: self.resolution.unwrap_or(20),
                rules: self.rules,
                max_events: self.max_events,
                scene,
                out,
            }),
            (false, true) => Mode::Map(MapArgs { resolution: self.resolution.unwrap_or(40), out }),
            (true, false) => match (self.thin_layer, self.heights, self.dc) {
                (Some(t_over_l), _, _) => Mode::ThinLayer(ThinLayerArgs { t_over_l, rg, scene, out }),
                (_, Some(h_over_l), _) => Mode::Heights(HeightsArgs { h_over_l, rg, scene, out }),
                (_, _, Some(dc)) => Mode::Dc(DcArgs { dc, rg, max_events: self.max_events, scene, out }),
                _ => Mode::Fe(FeArgs {
                    rg,
                    cycles: self.cycles.unwrap_or(tribofe::studies::precursors_fe::DEFAULT_FIG4_CYCLES),
                    residual: Default::default(),
                    backslip: "allowed".into(),
                    scene,
                    out,
                }),
            },
            (false, false) if self.bonded_fields => Mode::Bonded(BondedArgs {
                rg,
                events: self.events.unwrap_or(MAX_DEFAULT_EVENTS),
                sweep: self.sweep,
                scene,
                out,
            }),
            (false, false) => Mode::Model(ModelArgs { rg, events: self.events, out }),
        })
    }
}
