//! The dissertation's tests 1-7 (sections 5.5-5.6) and its Figure 20 (section 4.1)
//! on the simulated robots: each `testN_*` module and `fig20_fetch_boxes` runs its
//! experiment and returns what it measured and what its picture needs; [`run_all`]
//! runs them at once; [`doc`] writes `docs/experiments.md` from them, beside the
//! dissertation's figures.
//!
//! Every run is deterministic: a test's world, robot and seed give the same numbers
//! on every machine, whichever thread runs it.

pub mod controller;
pub mod cost;
pub mod doc;
pub mod fig20_fetch_boxes;
pub mod harness;
pub mod picture;
pub mod predictions;
pub mod seeds;
pub mod settings;
pub mod stats;
pub mod test1_turn;
pub mod test2_turn_left;
pub mod test3_followwall;
pub mod test4_obstacle;
pub mod test5_short_task;
pub mod test6_loop;
pub mod test7_way_out;

use ilmr_plot::Figure;

/// Everything the report is made of.
#[derive(Debug, Clone)]
pub struct Experiments {
    pub settings: settings::Settings,
    pub test1: test1_turn::Test1,
    pub predictions: predictions::Predictions,
    pub controller: controller::Comparison,
    pub test2: test2_turn_left::Test2,
    pub test3: test3_followwall::Test3,
    pub test4: test4_obstacle::Test4,
    pub test5: test5_short_task::Test5,
    pub test6: test6_loop::Test6,
    pub test7: test7_way_out::Test7,
    pub fig20: fig20_fetch_boxes::Fig20,
}

/// The pictures' file names (in `experiments/` beside the report): one per
/// experiment, then the spreads of Test 1 and Test 5 over their seeds.
pub const PICTURES: [&str; 10] = [
    "test1_turn.svg",
    "test2_turn_left.svg",
    "test3_followwall.svg",
    "test4_obstacle.svg",
    "test5_short_task.svg",
    "test6_loop.svg",
    "test7_way_out.svg",
    "fig20_fetch_boxes.svg",
    "test1_spread.svg",
    "test5_spread.svg",
];

/// What one run (or the runs of one test) cost; see [`cost`].
#[derive(Debug, Clone)]
pub struct Costed {
    pub name: &'static str,
    pub cost: cost::Cost,
}

type Handle<'s, T> = std::thread::ScopedJoinHandle<'s, (Result<T, String>, cost::Cost)>;

fn spawn<'s, T: Send + 's>(
    s: &'s std::thread::Scope<'s, '_>,
    f: impl FnOnce() -> Result<T, String> + Send + 's,
) -> Handle<'s, T> {
    s.spawn(|| cost::measure(f))
}

fn joined<T>(h: Handle<'_, T>, name: &'static str, costs: &mut Vec<Costed>) -> Result<T, String> {
    let (out, cost) = h.join().map_err(|_| format!("{name} panicked"))?;
    costs.push(Costed { name, cost });
    out.map_err(|e| format!("{name}: {e}"))
}

/// All the experiments, the statistical ones over `seeds` seeds (the report:
/// [`seeds::FULL`]), each run on its own thread (Figure 20's five runs each on
/// theirs).
pub fn run_all(seeds: usize) -> Result<Experiments, String> {
    run_all_costed(seeds).map(|(e, _)| e)
}

/// As [`run_all`], with what each run cost, in the order of the report.
pub fn run_all_costed(seeds: usize) -> Result<(Experiments, Vec<Costed>), String> {
    use fig20_fetch_boxes as f20;
    use predictions as p;
    let n = seeds;
    std::thread::scope(|s| {
        let t1 = spawn(s, test1_turn::run);
        let p2 = spawn(s, move || p::test2(n));
        let p3 = spawn(s, move || p::test3(n));
        let p4 = spawn(s, move || p::test4(n));
        let p5 = spawn(s, move || p::test5(n));
        let p6 = spawn(s, move || p::test6(n));
        let p7 = spawn(s, move || p::test7(n));
        let p20 = spawn(s, move || p::fig20(n));
        let co = spawn(s, move || controller::run(n, n));
        let t2 = spawn(s, test2_turn_left::run);
        let t3 = spawn(s, test3_followwall::run);
        let t4 = spawn(s, test4_obstacle::run);
        let t5 = spawn(s, test5_short_task::run);
        let t6 = spawn(s, test6_loop::run);
        let t7 = spawn(s, test7_way_out::run);
        let corrected = spawn(s, f20::corrected);
        let printed = spawn(s, f20::printed);
        let workpartner = spawn(s, f20::workpartner_in_the_office);
        let yard = spawn(s, f20::takebox_in_the_yard);
        let low_battery = spawn(s, f20::low_battery);
        let mut costs = Vec::new();
        let c = &mut costs;
        let experiments = Experiments {
            settings: settings::Settings::of_both()?,
            test1: joined(t1, "test 1", c)?,
            predictions: p::Predictions {
                seeds: n,
                test2: joined(p2, "test 2, calibrated, all seeds", c)?,
                test3: joined(p3, "test 3, calibrated, all seeds", c)?,
                test4: joined(p4, "test 4, calibrated, all seeds", c)?,
                test5: joined(p5, "test 5, calibrated, all seeds", c)?,
                test6: joined(p6, "test 6, calibrated, all seeds", c)?,
                test7: joined(p7, "test 7, calibrated, all seeds", c)?,
                fig20: joined(p20, "Figure 20, calibrated, all seeds", c)?,
            },
            controller: joined(co, "the controller, dissertation vs project", c)?,
            test2: joined(t2, "test 2", c)?,
            test3: joined(t3, "test 3", c)?,
            test4: joined(t4, "test 4", c)?,
            test5: joined(t5, "test 5", c)?,
            test6: joined(t6, "test 6", c)?,
            test7: joined(t7, "test 7", c)?,
            fig20: f20::Fig20 {
                corrected: joined(corrected, "Figure 20, MoRo, corrected", c)?,
                printed: joined(printed, "Figure 20, MoRo, as printed", c)?,
                workpartner: joined(workpartner, "Figure 20, Workpartner in the office", c)?,
                yard: joined(yard, "Figure 20, Workpartner's Takebox in the yard", c)?,
                low_battery: joined(low_battery, "Figure 20, MoRo, low battery", c)?,
                office: f20::office()?,
            },
        };
        Ok((experiments, costs))
    })
}

impl Experiments {
    /// Each experiment's picture with its file name from [`PICTURES`].
    pub fn figures(&self) -> [(&'static str, Figure); 10] {
        [
            (PICTURES[0], self.test1.figure()),
            (PICTURES[1], self.test2.figure()),
            (PICTURES[2], self.test3.figure()),
            (PICTURES[3], self.test4.figure()),
            (PICTURES[4], self.test5.figure()),
            (PICTURES[5], self.test6.figure()),
            (PICTURES[6], self.test7.figure()),
            (PICTURES[7], self.fig20.figure()),
            (PICTURES[8], self.test1.spread_figure()),
            (PICTURES[9], self.predictions.test5.spread_figure()),
        ]
    }
}
