//! The dissertation's tests 1-7 (sections 5.5-5.6) and its Figure 20 (section 4.1)
//! on the simulated robots: each `testN_*` module and `fig20_fetch_boxes` runs its
//! experiment and returns what it measured and what its picture needs; [`run_all`]
//! runs them at once; [`doc`] writes `docs/experiments.md` from them, beside the
//! dissertation's figures.
//!
//! Every run is deterministic: a test's world, robot and seed give the same numbers
//! on every machine, whichever thread runs it.

pub mod cost;
pub mod doc;
pub mod fig20_fetch_boxes;
pub mod harness;
pub mod picture;
pub mod predictions;
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
    pub test2: test2_turn_left::Test2,
    pub test3: test3_followwall::Test3,
    pub test4: test4_obstacle::Test4,
    pub test5: test5_short_task::Test5,
    pub test6: test6_loop::Test6,
    pub test7: test7_way_out::Test7,
    pub fig20: fig20_fetch_boxes::Fig20,
}

/// The pictures' file names (in `experiments/` beside the report), one per
/// experiment.
pub const PICTURES: [&str; 8] = [
    "test1_turn.svg",
    "test2_turn_left.svg",
    "test3_followwall.svg",
    "test4_obstacle.svg",
    "test5_short_task.svg",
    "test6_loop.svg",
    "test7_way_out.svg",
    "fig20_fetch_boxes.svg",
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

/// All the experiments, each run on its own thread (Figure 20's five runs each on
/// theirs).
pub fn run_all() -> Result<Experiments, String> {
    run_all_costed().map(|(e, _)| e)
}

/// As [`run_all`], with what each run cost, in the order of the report.
pub fn run_all_costed() -> Result<(Experiments, Vec<Costed>), String> {
    use fig20_fetch_boxes as f20;
    std::thread::scope(|s| {
        let t1 = spawn(s, test1_turn::run);
        let pr = spawn(s, predictions::run);
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
            predictions: joined(pr, "predictions (tests 2, 3, 5 calibrated)", c)?,
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
    pub fn figures(&self) -> [(&'static str, Figure); 8] {
        [
            (PICTURES[0], self.test1.figure()),
            (PICTURES[1], self.test2.figure()),
            (PICTURES[2], self.test3.figure()),
            (PICTURES[3], self.test4.figure()),
            (PICTURES[4], self.test5.figure()),
            (PICTURES[5], self.test6.figure()),
            (PICTURES[6], self.test7.figure()),
            (PICTURES[7], self.fig20.figure()),
        ]
    }
}
