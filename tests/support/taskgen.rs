//! Random VALID task files, drawn from the stdlib catalogue's grammars (forms, params,
//! ranges, variable kinds) and the robot models, for the fuzzers' corpus, the
//! generator's own tests and the soak test.
//!
//! A task is generated against one or more models at once and uses only what all of
//! them have (names in every model, the tightest of their limits), so the same task
//! checks on each. Every generated task checks with no diagnostic at all, and runs to
//! an end: every movement has a distance or is broken after a wait, loops count to a
//! bound, `stop` is followed by `cont`.
//!
//! ```ignore
//! let gen = Generator::new(&[&moro, &workpartner], Shape::default());
//! let task = gen.generate(seed); // task.task, task.skills
//! ```

use ilmr_geometry::SplitMix64;
use ilmr_model::RobotModel;
use ilmr_stdlib::{Command, Form, ModelNames, NameSpace, Occurs, ParamKind, Range, Unit, VarKind};

/// How big and how far-reaching a generated task is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shape {
    /// Top-level blocks (they start together): 1 to this many.
    pub max_blocks: usize,
    /// Statements per block before closing uses are added: 1 to this many.
    pub max_statements: usize,
    /// Nesting of `if` and `while`.
    pub max_depth: usize,
    /// Skills in the generated skill file (0: none, and no calls).
    pub max_skills: usize,
    /// Where absolute coordinates (`gotoxy(x,y)`, `createpath`) are drawn around: the
    /// robot's start in the world the task will run in.
    pub origin: (f64, f64),
    /// Largest distance of one movement and of absolute points from `origin`, m.
    pub reach: f64,
    /// Longest `wait(seconds)`, s.
    pub max_wait: f64,
    /// Searches (`sensor(scanner,door)`, `findtarget`): they run until they find
    /// their object, which in an empty world is never, so a task without them ends.
    pub searches: bool,
}

impl Default for Shape {
    fn default() -> Shape {
        Shape {
            max_blocks: 3,
            max_statements: 7,
            max_depth: 2,
            max_skills: 2,
            origin: (0.0, 0.0),
            reach: 1.5,
            max_wait: 2.0,
            searches: true,
        }
    }
}

/// A generated program: the task, and a skill file when the task calls skills
/// (pass it as a library: `Source::library`, or a file in the `--skills` directory).
#[derive(Debug, Clone, PartialEq)]
pub struct Generated {
    pub seed: u64,
    pub task: String,
    pub skills: Option<String>,
}

/// What every one of the given models has.
#[derive(Debug, Clone)]
struct Facts {
    /// Sensors (`[SENSORSANDACTUATORS]` ids below 10, as in the shipped models) and
    /// their reading counts.
    sensors: Vec<(String, u32)>,
    /// Actuators (ids 10 and up) and their ranges.
    actuators: Vec<(String, f64, f64)>,
    objects: Vec<String>,
    identifiers: Vec<String>,
    /// `[PARAMETERS]` names with their smallest value.
    parameters: Vec<(String, f64)>,
}

impl Facts {
    fn of(models: &[&RobotModel]) -> Facts {
        let first = models.first();
        let in_all = |has: &dyn Fn(&RobotModel) -> bool| models.iter().all(|m| has(m));
        let mut sensors = Vec::new();
        let mut actuators = Vec::new();
        for d in first.map(|m| m.devices.as_slice()).unwrap_or(&[]) {
            let same: Vec<_> = models.iter().filter_map(|m| m.device(&d.name)).collect();
            if same.len() != models.len() {
                continue;
            }
            if same.iter().all(|x| x.id < 10) {
                let readings = same.iter().map(|x| x.readings).min().unwrap_or(0);
                sensors.push((d.name.clone(), readings));
            } else if same.iter().all(|x| x.id >= 10) {
                let lo = same.iter().map(|x| x.min).fold(f64::MIN, f64::max);
                let hi = same.iter().map(|x| x.max).fold(f64::MAX, f64::min);
                if lo <= hi {
                    actuators.push((d.name.clone(), lo, hi));
                }
            }
        }
        let objects = first
            .map(|m| m.objects.iter().map(|o| o.name.clone()).collect::<Vec<_>>())
            .unwrap_or_default()
            .into_iter()
            .filter(|n| in_all(&|m: &RobotModel| m.object(n).is_some()))
            .collect();
        let identifiers = first
            .map(|m| {
                m.identifiers
                    .iter()
                    .map(|i| i.name.clone())
                    .collect::<Vec<_>>()
            })
            .unwrap_or_default()
            .into_iter()
            .filter(|n| in_all(&|m: &RobotModel| m.identifier(n).is_some()))
            .collect();
        let parameters = first
            .map(|m| {
                m.parameters
                    .iter()
                    .map(|p| p.name.clone())
                    .collect::<Vec<_>>()
            })
            .unwrap_or_default()
            .into_iter()
            .filter_map(|n| {
                let values: Option<Vec<f64>> =
                    models.iter().map(|m| m.parameter_or_default(&n)).collect();
                let v = values?.into_iter().fold(f64::MAX, f64::min);
                v.is_finite().then_some((n, v))
            })
            .collect();
        Facts {
            sensors,
            actuators,
            objects,
            identifiers,
            parameters,
        }
    }

    fn parameter(&self, name: &str) -> Option<f64> {
        self.parameters
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|(_, v)| *v)
    }

    fn sensor(&self, name: &str) -> Option<u32> {
        self.sensors
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|(_, r)| *r)
    }

    fn identifier(&self, name: &str) -> bool {
        self.identifiers
            .iter()
            .any(|n| n.eq_ignore_ascii_case(name))
    }
}

/// SplitMix64 (ilmr-geometry's), so that a seed means the same task on every machine.
#[derive(Debug, Clone)]
struct Rng(SplitMix64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0.next_u64()
    }

    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }

    fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }

    /// Uniform in `lo..=hi`, rounded to a twentieth so the text stays short.
    fn real(&mut self, lo: f64, hi: f64) -> f64 {
        let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        let unit = self.0.uniform();
        let v = ((lo + unit * (hi - lo)) * 20.0).round() / 20.0;
        v.clamp(lo, hi)
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> Option<&'a T> {
        items.get(self.below(items.len()))
    }
}

/// Numbers as the generator writes them: short, never `-0`.
fn num(v: f64) -> String {
    let text = format!("{v:.2}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    match text {
        "-0" | "" => "0".to_string(),
        t => t.to_string(),
    }
}

/// A variable bound by a generated statement.
#[derive(Debug, Clone)]
struct Var {
    name: String,
    kind: VarKind,
    used: bool,
    /// What bound it, so that a `break` can name exactly that statement.
    command: Option<Command>,
    /// The block whose statement bound it.
    block: usize,
}

/// The state of one program (task or skill) being written.
#[derive(Debug)]
struct Program<'g> {
    g: &'g Generator,
    rng: Rng,
    lines: Vec<String>,
    /// In scope: bound by a statement above, in this body or an enclosing one.
    vars: Vec<Var>,
    /// Paths that exist (created, or recorded and closed) for `followpath`.
    paths: Vec<String>,
    /// Skills the program may call.
    callable: Vec<String>,
    /// Prefix of every name this program makes, so that skills and the task never
    /// bind one variable with two kinds, and no name is a substring of another
    /// program's `v = command` (break patterns stay unique).
    prefix: String,
    skill: bool,
    /// Above zero inside a `while` body and in skills: what is written there must
    /// end by itself (a loop's next iteration and a skill's caller wait for it), so
    /// no searches that may find nothing, no guards that may never hold, no
    /// abstract turns that may follow a wall for ever.
    must_end: usize,
    next: usize,
    /// Serial of each open block, innermost last; a variable records the block that
    /// bound it.
    open: Vec<usize>,
    blocks_made: usize,
    /// Variables already named by a `break`: a second break of one would match two
    /// statements.
    broken: Vec<String>,
    /// The first statement written for each setting (`speed`, `bodypose`, an
    /// actuator): later ones repeat it, since blocks that start together and set one
    /// thing to two values race (W0905) and the program must check clean.
    settings: Vec<(String, String)>,
}

#[derive(Debug, Clone)]
pub struct Generator {
    facts: Facts,
    shape: Shape,
}

/// The commands the generic call generator draws from, with weights. Control flow,
/// `record`, `stop`/`cont` and the unbounded movements have their own patterns.
const CALLS: &[(Command, usize)] = &[
    (Command::Speed, 4),
    (Command::ObsAvoid, 2),
    (Command::AdvanceStop, 1),
    (Command::Use, 1),
    (Command::LocMode, 1),
    (Command::MoveMode, 1),
    (Command::BodyPose, 1),
    (Command::SavePos, 2),
    (Command::CreatePath, 1),
    (Command::Goahead, 6),
    (Command::Turn, 4),
    (Command::FollowPath, 2),
    (Command::GotoXY, 2),
    (Command::GotoRelXY, 2),
    (Command::Approach, 1),
    (Command::Sensor, 4),
    (Command::FindTarget, 1),
    (Command::Actuator, 1),
    (Command::Manipulate, 1),
    (Command::Init, 1),
];

impl Generator {
    pub fn new(models: &[&RobotModel], shape: Shape) -> Generator {
        Generator {
            facts: Facts::of(models),
            shape,
        }
    }

    pub fn generate(&self, seed: u64) -> Generated {
        let mut rng = Rng(SplitMix64::new(seed ^ 0x5EED_1A5C_0FFE_E000));
        let skill_count = if self.shape.max_skills == 0 {
            0
        } else {
            rng.below(self.shape.max_skills + 1)
        };
        let mut skill_text = String::new();
        let mut skills: Vec<String> = Vec::new();
        // One value per setting across the skills and the task (a skill's settings
        // are made in its caller's tick).
        let mut settings = Vec::new();
        for i in 0..skill_count {
            let name = format!("Skill{}", i + 1);
            let mut p = Program::new(
                self,
                Rng(SplitMix64::new(rng.next())),
                &format!("s{}_", i + 1),
            );
            p.settings = std::mem::take(&mut settings);
            p.skill = true;
            p.must_end = 1;
            // A skill calls only the skills before it: never recursion.
            p.callable = skills.clone();
            let count = 1 + p.rng.below(2);
            let body = p.blocks(count, 0);
            skill_text.push_str(&format!("{name}:\n{body}\n"));
            skills.push(name);
            settings = p.settings;
        }
        let mut p = Program::new(self, Rng(SplitMix64::new(rng.next())), "t");
        p.settings = settings;
        p.callable = skills;
        let blocks = 1 + p.rng.below(self.shape.max_blocks.max(1));
        let task = p.blocks(blocks, 0);
        Generated {
            seed,
            task,
            skills: (skill_count > 0).then_some(skill_text),
        }
    }
}

impl<'g> Program<'g> {
    fn new(g: &'g Generator, rng: Rng, prefix: &str) -> Program<'g> {
        Program {
            g,
            rng,
            lines: Vec::new(),
            vars: Vec::new(),
            paths: Vec::new(),
            callable: Vec::new(),
            prefix: prefix.to_string(),
            skill: false,
            must_end: 0,
            next: 0,
            open: Vec::new(),
            blocks_made: 0,
            broken: Vec::new(),
            settings: Vec::new(),
        }
    }

    fn fresh(&mut self, letter: &str) -> String {
        self.next += 1;
        format!("{}{letter}{}", self.prefix, self.next)
    }

    fn bind(&mut self, letter: &str, kind: VarKind, command: Option<Command>) -> String {
        let name = self.fresh(letter);
        self.declare(&name, kind, command);
        name
    }

    fn declare(&mut self, name: &str, kind: VarKind, command: Option<Command>) {
        self.vars.push(Var {
            name: name.to_string(),
            kind,
            used: false,
            command,
            block: self.open.last().copied().unwrap_or(0),
        });
    }

    fn use_var(&mut self, name: &str) {
        if let Some(v) = self.vars.iter_mut().find(|v| v.name == name) {
            v.used = true;
        }
    }

    fn emit(&mut self, depth: usize, text: impl AsRef<str>) {
        let text = self.one_value_per_setting(text.as_ref());
        self.lines.push(format!("{}{}", "    ".repeat(depth), text));
    }

    /// `text`, or the statement first written for the setting it makes. The random
    /// draws are made as before, so the rest of the program does not change.
    fn one_value_per_setting(&mut self, text: &str) -> String {
        use ilmr_stdlib::Sets;
        let (bound, call) = match text.split_once(" = ") {
            Some((v, call)) => (Some(v), call),
            None => (None, text),
        };
        let Some((name, args)) = call.split_once('(') else {
            return text.to_string();
        };
        let Some(command) = Command::from_name(name) else {
            return text.to_string();
        };
        let words = args.trim_end_matches(')').split(',').map(str::trim);
        let target = match command.spec().sets.applies(words) {
            Sets::Nothing => return text.to_string(),
            Sets::Setting { what, .. } => what.to_string(),
            Sets::Device => format!("{name}:{}", args.split(',').next().unwrap_or("")),
        };
        let first = match self.settings.iter().find(|(t, _)| *t == target) {
            Some((_, first)) => first.clone(),
            None => {
                self.settings.push((target, call.to_string()));
                call.to_string()
            }
        };
        match bound {
            Some(v) => format!("{v} = {first}"),
            None => first,
        }
    }

    /// `count` blocks separated by empty lines, as text.
    fn blocks(&mut self, count: usize, depth: usize) -> String {
        for i in 0..count {
            if i > 0 {
                self.lines.push(String::new());
            }
            self.block(depth);
        }
        let text = self.lines.join("\n") + "\n";
        self.lines.clear();
        text
    }

    /// One block: statements, then a use of every variable the block bound and
    /// nothing read. Variables bound in a nested body go out of scope at its end, so
    /// nothing relies on a guard's body having run.
    fn block(&mut self, depth: usize) {
        self.blocks_made += 1;
        self.open.push(self.blocks_made);
        let scope = self.vars.len();
        let statements = 1 + self.rng.below(self.g.shape.max_statements.max(1));
        for _ in 0..statements {
            self.statement(depth);
        }
        let unused: Vec<Var> = self.vars[scope..]
            .iter()
            .filter(|v| !v.used)
            .cloned()
            .collect();
        for v in unused {
            self.consume(depth, &v);
        }
        if depth > 0 {
            self.vars.truncate(scope);
        }
        self.open.pop();
    }

    /// Reads a variable so that it is not left unused, in the way its kind suggests.
    fn consume(&mut self, depth: usize, v: &Var) {
        self.use_var(&v.name);
        match v.kind {
            // A found or saved position: go there once it is known.
            VarKind::Position => {
                let go = match self.rng.below(3) {
                    0 => format!("turn({})", v.name),
                    1 => format!("approach({},{})", v.name, num(self.rng.real(0.5, 1.5))),
                    _ => format!("gotoxy({})", v.name),
                };
                self.emit(depth, format!("if({})", v.name));
                self.emit(depth + 1, go);
                self.emit(depth, "endif");
            }
            VarKind::Number | VarKind::Reading => self.emit(depth, format!("clear({})", v.name)),
            VarKind::Status | VarKind::Movement => self.emit(depth, format!("wait({})", v.name)),
        }
    }

    fn statement(&mut self, depth: usize) {
        let nest = depth < self.g.shape.max_depth;
        match self.rng.below(20) {
            0 if nest => self.guard(depth),
            1 if nest => self.counted_loop(depth),
            2 => self.arithmetic(depth),
            3 => self.wait(depth),
            4 => self.bounded(depth),
            5 => self.recording(depth),
            6 => self.pause(depth),
            7 if !self.callable.is_empty() => self.call_skill(depth),
            8 => self.break_one(depth),
            9 if depth == 0 && !self.skill => self.battery_priority(depth),
            _ => self.call(depth),
        }
    }

    /// A command of the catalogue, generated from one of its forms.
    fn call(&mut self, depth: usize) {
        // A command needing a device some robot lacks (`manipulate` on MoRo) would not
        // check clean on that robot: it is not drawn.
        let facts = &self.g.facts;
        let has = |d: &str| {
            facts.sensors.iter().any(|(n, _)| n.eq_ignore_ascii_case(d))
                || facts
                    .actuators
                    .iter()
                    .any(|(n, ..)| n.eq_ignore_ascii_case(d))
        };
        let calls: Vec<(Command, usize)> = CALLS
            .iter()
            .copied()
            .filter(|(c, _)| c.spec().needs_device.is_none_or(has))
            .collect();
        let total: usize = calls.iter().map(|(_, w)| w).sum();
        let mut roll = self.rng.below(total);
        let command = calls
            .iter()
            .find(|(_, w)| {
                if roll < *w {
                    true
                } else {
                    roll -= w;
                    false
                }
            })
            .map_or(Command::Goahead, |(c, _)| *c);
        let spec = command.spec();
        let mut forms: Vec<&Form> = spec.forms.iter().collect();
        // Try the forms in a random order; the first one the program can fill wins.
        for i in (1..forms.len()).rev() {
            forms.swap(i, self.rng.below(i + 1));
        }
        for form in forms {
            if let Some(args) = self.args(command, form) {
                let text = if args.is_empty() && spec.allows_bare() && self.rng.chance(50) {
                    spec.name.to_string()
                } else {
                    format!("{}({})", spec.name, args.join(","))
                };
                self.issue(depth, command, form.produces, &text);
                return;
            }
        }
        let v = self.speed();
        self.emit(depth, format!("speed({})", num(v)));
    }

    /// Emits `text`, bound to a new variable when the program will use it.
    fn issue(&mut self, depth: usize, command: Command, kind: VarKind, text: &str) {
        if command == Command::SavePos {
            // `savepos(name)` binds `name` itself.
            self.emit(depth, text);
            return;
        }
        let spec = command.spec();
        let bind = spec.movement || kind == VarKind::Position || self.rng.chance(30);
        if bind {
            let letter = match kind {
                VarKind::Movement => "m",
                VarKind::Position => "p",
                VarKind::Reading => "r",
                VarKind::Number => "n",
                VarKind::Status => "d",
            };
            let name = self.bind(letter, kind, Some(command));
            self.emit(depth, format!("{name} = {text}"));
        } else {
            self.emit(depth, text);
        }
    }

    /// Arguments for `form`, or `None` when this program cannot fill it.
    fn args(&mut self, command: Command, form: &Form) -> Option<Vec<String>> {
        let mut args = Vec::new();
        let mut device: Option<String> = None;
        let searching = form.produces == VarKind::Position && command != Command::SavePos;
        if searching && (self.must_end > 0 || !self.g.shape.searches) {
            return None;
        }
        for param in form.params {
            let count = match param.occurs {
                Occurs::One => 1,
                Occurs::Optional => usize::from(self.optional(command, param.name)),
                Occurs::Many => self.rng.below(3),
                Occurs::Pairs => 2 * (1 + self.rng.below(3)),
            };
            for _ in 0..count {
                let arg = self.arg(command, param.name, &param.kind, &mut device, searching)?;
                args.push(arg);
            }
        }
        (args.len() >= usize::from(form.min_args)).then_some(args)
    }

    /// Whether an optional parameter is given. Some never are: `forever` (its own
    /// pattern), a pointing device for `savepos`; a distance for `goahead` always is.
    fn optional(&mut self, command: Command, param: &str) -> bool {
        match (command, param) {
            (_, "forever") | (Command::SavePos, "device") => false,
            (Command::Goahead, "distance") => true,
            _ => self.rng.chance(50),
        }
    }

    fn arg(
        &mut self,
        command: Command,
        param: &str,
        kind: &ParamKind,
        device: &mut Option<String>,
        searching: bool,
    ) -> Option<String> {
        let g = self.g;
        let facts = &g.facts;
        match *kind {
            // `turn(left)` follows the wall until there is room, which may be never.
            ParamKind::Keyword { .. } if command == Command::Turn && self.must_end > 0 => None,
            ParamKind::Keyword { words } => self.rng.pick(words).map(|w| w.to_string()),
            ParamKind::Mode { words, .. } => {
                let usable: Vec<&str> = words
                    .iter()
                    .copied()
                    .filter(|w| facts.identifier(w))
                    .collect();
                self.rng.pick(&usable).map(|w| w.to_string())
            }
            ParamKind::Value { unit, range } => {
                let v = self.value(command, param, unit, range, device.as_deref())?;
                Some(num(v))
            }
            ParamKind::Setting { key, unit, range } => {
                let v = self.value(command, key, unit, range, device.as_deref())?;
                Some(format!("{key}={}", num(v)))
            }
            ParamKind::Model { names } => {
                let choices: Vec<String> = match (names, command) {
                    (ModelNames::Device, Command::Actuator) => {
                        facts.actuators.iter().map(|a| a.0.clone()).collect()
                    }
                    // `approach(door)` reads `door` as a variable first.
                    (ModelNames::Object, Command::Approach) => Vec::new(),
                    (ModelNames::Device, Command::FindTarget | Command::Sensor) if searching => {
                        ["scanner"]
                            .iter()
                            .filter(|s| facts.sensor(s).is_some())
                            .map(|s| s.to_string())
                            .collect()
                    }
                    (ModelNames::Device, _) => facts.sensors.iter().map(|s| s.0.clone()).collect(),
                    (ModelNames::Object, _) => facts.objects.clone(),
                    (ModelNames::Service, _) => facts
                        .identifiers
                        .iter()
                        .filter(|i| i.eq_ignore_ascii_case("navi"))
                        .cloned()
                        .chain(facts.sensors.iter().map(|s| s.0.clone()))
                        .collect(),
                };
                let choice = self.rng.pick(&choices)?.clone();
                if names == ModelNames::Device {
                    *device = Some(choice.clone());
                }
                Some(choice)
            }
            // Only a position saved earlier in this block or one enclosing it is known
            // for certain when the command starts (blocks run concurrently, searches
            // may find nothing); `gotorelxy` would take an absolute one as relative.
            ParamKind::Position if command == Command::GotoRelXY => None,
            ParamKind::Position => {
                let positions: Vec<String> = self
                    .vars
                    .iter()
                    .filter(|v| {
                        v.kind == VarKind::Position
                            && v.command == Some(Command::SavePos)
                            && self.open.contains(&v.block)
                    })
                    .map(|v| v.name.clone())
                    .collect();
                let name = self.rng.pick(&positions)?.clone();
                self.use_var(&name);
                Some(name)
            }
            ParamKind::Variable => {
                let names: Vec<String> = self.vars.iter().map(|v| v.name.clone()).collect();
                let name = self.rng.pick(&names)?.clone();
                self.use_var(&name);
                Some(name)
            }
            ParamKind::Name { space } => match (space, command) {
                (NameSpace::Path, Command::FollowPath) => self.rng.pick(&self.paths).cloned(),
                (NameSpace::Path, Command::CreatePath) => {
                    let name = self.fresh("path");
                    self.paths.push(name.clone());
                    Some(name)
                }
                (NameSpace::SavedPosition, _) => {
                    Some(self.bind("p", VarKind::Position, Some(Command::SavePos)))
                }
                // `record` has its own pattern.
                _ => None,
            },
            ParamKind::OneOf { kinds } => {
                let start = self.rng.below(kinds.len());
                (0..kinds.len()).find_map(|i| {
                    let kind = &kinds[(start + i) % kinds.len()];
                    self.arg(command, param, kind, device, searching)
                })
            }
        }
    }

    /// A number inside `range` (with the models' tightest limits) that keeps the
    /// robot near where it is.
    fn value(
        &mut self,
        command: Command,
        param: &str,
        unit: Unit,
        range: Range,
        device: Option<&str>,
    ) -> Option<f64> {
        let g = self.g;
        let facts = &g.facts;
        let shape = self.g.shape;
        let (o, reach) = (shape.origin, shape.reach);
        Some(match (command, param, range) {
            (Command::Speed, _, _) => self.speed(),
            (Command::Turn, "d", _) => {
                let a = self.rng.real(30.0, 180.0);
                if self.rng.chance(50) { -a } else { a }
            }
            (Command::GotoXY, "x", _) => self.rng.real(o.0 - reach, o.0 + reach),
            (Command::GotoXY, "y", _) => self.rng.real(o.1 - reach, o.1 + reach),
            (Command::CreatePath, _, _) => {
                // Pairs alternate x and y; both stay near the origin.
                let centre = if self.next.is_multiple_of(2) {
                    o.0
                } else {
                    o.1
                };
                self.next += 1;
                self.rng.real(centre - reach, centre + reach)
            }
            (Command::GotoRelXY, "x", _) => self.rng.real(0.5, reach.max(0.5)),
            (Command::GotoRelXY, "y", _) => self.rng.real(-reach / 2.0, reach / 2.0),
            (_, _, Range::Between { min, max, .. }) => {
                let (lo, hi) = match unit {
                    Unit::Degrees => (min.max(-180.0), max.min(180.0)),
                    _ => (min, max),
                };
                self.rng.real(lo, hi)
            }
            (_, _, Range::Any) => match unit {
                Unit::Metres => {
                    let d = self.rng.real(0.2, reach);
                    if self.rng.chance(20) { -d } else { d }
                }
                Unit::Degrees => self.rng.real(-180.0, 180.0),
                _ => self.rng.real(0.0, 1.0),
            },
            (_, _, Range::Positive) => self.rng.real(0.3, reach.max(0.3)),
            (_, _, Range::NonNegative) => match unit {
                Unit::Seconds => self.rng.real(0.0, shape.max_wait),
                _ => self.rng.real(0.0, reach),
            },
            (_, _, Range::Symmetric { param, .. }) => {
                let limit = facts.parameter(param)?;
                self.rng.real(-limit, limit)
            }
            (_, _, Range::Magnitude { param, .. }) => {
                let limit = facts.parameter(param)?;
                self.rng.real((limit / 4.0).min(0.1), limit)
            }
            (_, _, Range::UpTo { param, .. }) => {
                let limit = facts.parameter(param)?;
                self.rng.real(0.0, limit)
            }
            (_, _, Range::DeviceRange) => {
                let name = device?;
                let (_, lo, hi) = facts.actuators.iter().find(|a| a.0 == name)?;
                self.rng.real(*lo, *hi).round().clamp(*lo, *hi)
            }
            (_, _, Range::ReadingIndex) => {
                let readings = facts.sensor(device?)?;
                if readings == 0 {
                    return None;
                }
                self.rng.below(readings as usize) as f64
            }
        })
    }

    /// A speed within `max_speed`, mostly forwards and never so slow that a run drags.
    fn speed(&mut self) -> f64 {
        let max = self.g.facts.parameter("max_speed").unwrap_or(0.5);
        let v = self.rng.real((0.4 * max).min(0.25), max * 0.9);
        if self.rng.chance(15) { -v } else { v }
    }

    /// `if(condition)` with a body, on a variable in scope.
    fn guard(&mut self, depth: usize) {
        let Some(cond) = self.condition() else {
            return self.call(depth);
        };
        self.emit(depth, format!("if({cond})"));
        self.block(depth + 1);
        self.emit(depth, "endif");
    }

    fn condition(&mut self) -> Option<String> {
        let must_end = self.must_end > 0;
        let candidates: Vec<Var> = self
            .vars
            .iter()
            .filter(|v| {
                !must_end
                    || matches!(v.kind, VarKind::Status | VarKind::Movement)
                    || v.command == Some(Command::SavePos)
            })
            .cloned()
            .collect();
        let v = self.rng.pick(&candidates)?.clone();
        self.use_var(&v.name);
        Some(match v.kind {
            VarKind::Position => {
                let others: Vec<String> = candidates
                    .iter()
                    .filter(|o| o.kind == VarKind::Position && o.name != v.name)
                    .map(|o| o.name.clone())
                    .collect();
                match self.rng.pick(&others).cloned() {
                    Some(o) if self.rng.chance(50) => {
                        self.use_var(&o);
                        format!("{} == {o}", v.name)
                    }
                    _ => v.name.clone(),
                }
            }
            VarKind::Movement if must_end => v.name.clone(),
            VarKind::Movement => format!("{} > {}", v.name, num(self.rng.real(0.1, 1.0))),
            VarKind::Reading if v.command == Some(Command::Sensor) => {
                match self.g.facts.parameter("LowBattery") {
                    Some(_) if self.rng.chance(50) => format!("{} < LowBattery", v.name),
                    _ => format!("{} >= {}", v.name, num(self.rng.real(0.0, 10.0))),
                }
            }
            VarKind::Number | VarKind::Reading => {
                let op = self.rng.pick(&["<", "<=", "==", ">", ">=", "!="]).copied();
                format!(
                    "{} {} {}",
                    v.name,
                    op.unwrap_or("<"),
                    num(self.rng.real(-2.0, 5.0))
                )
            }
            VarKind::Status => v.name.clone(),
        })
    }

    /// `k = 0`, `while(k < N)` ... `k = k + 1`: a loop that ends.
    fn counted_loop(&mut self, depth: usize) {
        let k = self.bind("k", VarKind::Number, None);
        self.use_var(&k);
        let bound = 1 + self.rng.below(3);
        self.emit(depth, format!("{k} = 0"));
        let head = format!("while({k} < {bound})");
        // The loop's own variable is declared after its body: its status is 1 only
        // when the loop has ended, so a guard on it inside would wait for ever.
        let bound_to = self.rng.chance(30).then(|| self.fresh("l"));
        match &bound_to {
            Some(l) => self.emit(depth, format!("{l} = {head}")),
            None => self.emit(depth, head),
        }
        self.must_end += 1;
        self.block(depth + 1);
        self.must_end -= 1;
        self.emit(depth + 1, format!("{k} = {k} + 1"));
        self.emit(depth, "endwhile");
        if let Some(l) = bound_to {
            self.declare(&l, VarKind::Status, None);
        }
    }

    /// `n = expression` over numbers, readings and model constants.
    fn arithmetic(&mut self, depth: usize) {
        let mut operands: Vec<String> = self
            .vars
            .iter()
            .filter(|v| matches!(v.kind, VarKind::Number | VarKind::Reading))
            .map(|v| v.name.clone())
            .collect();
        operands.extend(
            ["max_speed", "followwall_d", "bs_security"]
                .iter()
                .filter(|p| self.g.facts.parameter(p).is_some())
                .map(|p| p.to_string()),
        );
        let term = |p: &mut Program<'_>| -> String {
            match p.rng.pick(&operands).cloned() {
                Some(o) if p.rng.chance(60) => {
                    p.use_var(&o);
                    o
                }
                _ => num(p.rng.real(-5.0, 5.0)),
            }
        };
        let a = term(self);
        let op = self.rng.pick(&["+", "-", "*"]).copied().unwrap_or("+");
        // The second term is drawn only when it is written: drawing marks it used.
        let expr = match self.rng.below(3) {
            0 => a,
            1 => format!("{a} {op} {}", term(self)),
            _ => format!("({a} {op} {}) / 2", term(self)),
        };
        let n = self.bind("n", VarKind::Number, None);
        self.emit(depth, format!("{n} = {expr}"));
    }

    fn wait(&mut self, depth: usize) {
        let waitable: Vec<String> = self
            .vars
            .iter()
            .filter(|v| matches!(v.kind, VarKind::Movement | VarKind::Status))
            .map(|v| v.name.clone())
            .collect();
        match self.rng.pick(&waitable).cloned() {
            Some(v) if self.rng.chance(50) => {
                self.use_var(&v);
                self.emit(depth, format!("wait({v})"));
            }
            _ => {
                let s = self.rng.real(0.1, self.g.shape.max_wait);
                self.emit(depth, format!("wait({})", num(s)));
            }
        }
    }

    /// A command that runs until broken, and the wait and break that end it:
    /// `followwall`, `followtarget`, `goahead()`, or a search `forever`.
    fn bounded(&mut self, depth: usize) {
        let g = self.g;
        let facts = &g.facts;
        let mut options: Vec<(Command, String)> = Vec::new();
        let side = *self
            .rng
            .pick(&["left", "right", "middle"])
            .unwrap_or(&"left");
        options.push((Command::FollowWall, format!("followwall({side})")));
        options.push((Command::Goahead, "goahead()".into()));
        if let Some(object) = self.rng.pick(&facts.objects).cloned() {
            options.push((
                Command::FollowTarget,
                format!("followtarget({object},{})", num(self.rng.real(1.0, 3.0))),
            ));
            if facts.sensor("scanner").is_some() && g.shape.searches {
                options.push((Command::Sensor, format!("sensor(scanner,{object},forever)")));
            }
        }
        let Some((command, text)) = self.rng.pick(&options).cloned() else {
            return;
        };
        let kind = if command == Command::Sensor {
            VarKind::Position
        } else {
            VarKind::Movement
        };
        let name = self.bind(
            if command == Command::Sensor { "p" } else { "m" },
            kind,
            Some(command),
        );
        self.emit(depth, format!("{name} = {text}"));
        let s = self.rng.real(0.5, self.g.shape.max_wait);
        self.emit(depth, format!("wait({})", num(s)));
        // The pattern is the binding, which only this statement has.
        self.broken.push(name.clone());
        self.emit(depth, format!("break({name} = {})", command.name()));
        self.use_var(&name);
        if kind == VarKind::Movement {
            self.emit(depth, format!("wait({name})"));
        } else {
            // What it found, if anything, is not waited for.
            self.emit(depth, format!("clear({name})"));
        }
    }

    /// `record(path)` around a movement, then `record(close)`; the path can be
    /// followed afterwards.
    fn recording(&mut self, depth: usize) {
        let path = self.fresh("rec");
        self.emit(depth, format!("record({path})"));
        let d = self.rng.real(0.3, self.g.shape.reach);
        let m = self.bind("m", VarKind::Movement, Some(Command::Goahead));
        self.use_var(&m);
        self.emit(depth, format!("{m} = goahead({})", num(d)));
        self.emit(depth, format!("wait({m})"));
        self.emit(depth, "record(close)");
        self.paths.push(path);
    }

    /// `stop`, a wait, `cont`.
    fn pause(&mut self, depth: usize) {
        self.emit(depth, "stop");
        let s = self.rng.real(0.1, 1.0);
        self.emit(depth, format!("wait({})", num(s)));
        self.emit(depth, "cont");
    }

    fn call_skill(&mut self, depth: usize) {
        let Some(skill) = self.rng.pick(&self.callable).cloned() else {
            return;
        };
        if self.rng.chance(50) {
            let d = self.bind("d", VarKind::Status, None);
            self.emit(depth, format!("{d} = {skill}"));
        } else {
            self.emit(depth, skill);
        }
    }

    /// `break(v = command)` for a command bound above: ends it if it still runs.
    fn break_one(&mut self, depth: usize) {
        let targets: Vec<(String, Command)> = self
            .vars
            .iter()
            .filter_map(|v| v.command.map(|c| (v.name.clone(), c)))
            .filter(|(name, c)| *c != Command::SavePos && !self.broken.contains(name))
            .collect();
        match self.rng.pick(&targets).cloned() {
            Some((name, command)) => {
                self.broken.push(name.clone());
                self.emit(depth, format!("break({name} = {})", command.name()))
            }
            None => self.call(depth),
        }
    }

    /// Figure 20's battery watch: a block that takes over when the battery is low.
    fn battery_priority(&mut self, depth: usize) {
        let g = self.g;
        let facts = &g.facts;
        if depth > 0 || facts.sensor("battery").is_none() || facts.parameter("LowBattery").is_none()
        {
            return self.call(depth);
        }
        let b = self.bind("r", VarKind::Reading, Some(Command::Sensor));
        self.use_var(&b);
        self.emit(depth, format!("{b} = sensor(battery)"));
        self.emit(depth, format!("if({b} < LowBattery)"));
        self.emit(depth + 1, "priority = highest");
        let v = self.speed().abs();
        self.emit(depth + 1, format!("speed({})", num(v)));
        self.emit(depth, "endif");
    }
}
