//! `ilmrc shell`: the dissertation's `manager` and `pilot` (section 4.2) at a prompt.
//! A simulated robot runs in real time on its own thread (`crate::live`, as for
//! `serve`); a person types ILMR lines, each checked against the running task before
//! it joins. Line editing, history and completion are rustyline's, which reads plain
//! lines when stdin is not a terminal. Documented in docs/shell.md.

mod complete;
mod input;
mod piped;
mod show;

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use ilmr_compiler::render::Style;
use rustyline::error::ReadlineError;
use rustyline::history::FileHistory;
use rustyline::{CompletionType, Config, Editor, ExternalPrinter};

use crate::live::engine::{Job, LineAnswer, Outcome, Status};
use crate::live::reply::Reply;
use crate::live::{Live, RobotArgs};
use crate::notice::Detail;
use complete::{ShellHelper, Words};
use input::{Collector, Input, ShellCommand};

/// The VM thread answers between two ticks; this only guards against it having stopped.
const ANSWER_WAIT: Duration = Duration::from_secs(10);
/// Event lines queued for the notice thread before the engine drops it.
const EVENT_QUEUE: usize = 4096;
/// The shell's own subscription id on the engine (connections of `serve` count from 1).
const SHELL_SUBSCRIBER: u64 = 0;

#[derive(clap::Args)]
pub struct ShellArgs {
    #[command(flatten)]
    pub live: RobotArgs,
    /// Keep the typed lines in this file across sessions (read at start, written at
    /// the end); without it history lasts for the session only.
    #[arg(long)]
    pub history: Option<PathBuf>,
}

pub fn run(args: ShellArgs) -> ExitCode {
    match execute(&args) {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(crate::EXIT_USAGE)
        }
    }
}

fn execute(args: &ShellArgs) -> Result<ExitCode, String> {
    let Some(live) = crate::live::start(&args.live)? else {
        return Ok(ExitCode::from(crate::EXIT_ERRORS));
    };
    let terminal = std::io::stdin().is_terminal() && std::io::stdout().is_terminal();
    let style = Style::on_terminal(terminal);
    let words = Arc::new(Mutex::new(Words::new(&live.model)));
    let config = Config::builder()
        .auto_add_history(true)
        .completion_type(CompletionType::List)
        .build();
    let mut editor: Editor<ShellHelper, FileHistory> =
        Editor::with_config(config).map_err(|e| format!("cannot open the terminal: {e}"))?;
    editor.set_helper(Some(ShellHelper {
        words: Arc::clone(&words),
    }));
    if let Some(path) = args.history.as_ref().filter(|p| p.exists()) {
        // rustyline reads the file itself, without a limit; this read refuses what it
        // should not be given (a device, a FIFO, a huge file) first.
        ilmr_files::read(path, ilmr_files::Kind::History)
            .map_err(|e| format!("cannot read history `{}`: {e}", path.display()))?;
        editor
            .load_history(path)
            .map_err(|e| format!("cannot read history `{}`: {e}", path.display()))?;
    }
    let watch = Arc::new(AtomicBool::new(false));
    notices(&live.jobs, &mut editor, terminal, Arc::clone(&watch))?;
    let first = status(&live.jobs)?;
    refresh(&words, &first);
    println!(
        "ILMR shell: {} in {}, at x {} m, y {} m. Type ILMR lines; :help for help, :quit \
         or Ctrl-D to leave.",
        live.model.name,
        live.world,
        ilmr_vm::runtime::trace::fmt_num(first.pose.x),
        ilmr_vm::runtime::trace::fmt_num(first.pose.y)
    );
    let mut collector = Collector::default();
    // rustyline reads a pipe whole-line and unbounded, and ends at the first byte that
    // is not UTF-8; piped lines are read here instead.
    let mut piped = (!std::io::stdin().is_terminal())
        .then(|| piped::Piped::new(std::io::BufReader::new(std::io::stdin())));
    'typing: loop {
        let _ = std::io::stdout().flush();
        if let Some(p) = piped.as_mut() {
            match p.next_line() {
                Ok(Some(Ok(line))) => {
                    if act(collector.take(&line), &live, &words, &watch, style)? == Next::Quit {
                        break 'typing;
                    }
                }
                // A block missing one of its lines is not the block that was meant.
                Ok(Some(Err(why))) => match collector.cancel() {
                    true => println!("error: {why}, and the unfinished block was dropped"),
                    false => println!("error: {why}"),
                },
                Ok(None) => break,
                Err(e) => return Err(format!("cannot read a line: {e}")),
            }
            continue;
        }
        let typed = match editor.readline(collector.prompt()) {
            Ok(typed) => typed,
            Err(ReadlineError::Interrupted) => {
                let dropped = collector.cancel();
                println!(
                    "{}(:quit or Ctrl-D leaves; `stop` halts the robot)",
                    if dropped {
                        "dropped the unfinished block "
                    } else {
                        ""
                    }
                );
                continue;
            }
            Err(ReadlineError::Eof) => break,
            Err(e) => return Err(format!("cannot read a line: {e}")),
        };
        // A paste may hand over several lines at once; each is taken in turn.
        for line in typed.lines() {
            if act(collector.take(line), &live, &words, &watch, style)? == Next::Quit {
                break 'typing;
            }
        }
    }
    if let Some(path) = &args.history {
        editor
            .save_history(path)
            .map_err(|e| format!("cannot write history `{}`: {e}", path.display()))?;
    }
    let last = status(&live.jobs)?;
    println!(
        "left the shell at t={} s; the robot was at x {} m, y {} m",
        ilmr_vm::runtime::trace::fmt_num(last.t),
        ilmr_vm::runtime::trace::fmt_num(last.pose.x),
        ilmr_vm::runtime::trace::fmt_num(last.pose.y)
    );
    Ok(ExitCode::SUCCESS)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Next {
    Read,
    Quit,
}

/// Does what a typed line means and prints the answer.
fn act(
    input: Input,
    live: &Live,
    words: &Mutex<Words>,
    watch: &AtomicBool,
    style: Style,
) -> Result<Next, String> {
    let jobs = &live.jobs;
    match input {
        Input::Nothing | Input::More => {}
        Input::Note(note) => println!("{note}"),
        Input::Join(text) => {
            let answer = ask_line(jobs, |text, reply| Job::Line { text, reply }, &text)?;
            print!("{}", show::joined(&answer, &text, style));
            if matches!(answer.outcome, Outcome::Accepted { .. }) {
                refresh(words, &status(jobs)?);
            }
        }
        Input::Check(text) => {
            let answer = ask_line(jobs, |text, reply| Job::Check { text, reply }, &text)?;
            print!("{}", show::checked(&answer, &text, style));
        }
        Input::Shell(ShellCommand::Status) => print!("{}", show::status(&status(jobs)?)),
        Input::Shell(ShellCommand::Watch) => {
            let on = !watch.fetch_xor(true, Ordering::SeqCst);
            println!(
                "watch {}",
                if on {
                    "on: commands starting and ending are shown"
                } else {
                    "off"
                }
            );
        }
        Input::Shell(ShellCommand::Help) => print!("{}", show::HELP),
        Input::Shell(ShellCommand::Quit) => return Ok(Next::Quit),
    }
    Ok(Next::Read)
}

/// Sends `text` as a line or a check and waits for the answer.
fn ask_line(
    jobs: &Sender<Job>,
    job: impl FnOnce(String, Reply<LineAnswer>) -> Job,
    text: &str,
) -> Result<LineAnswer, String> {
    let (reply, answer) = mpsc::channel();
    let job = job(text.to_string(), reply.into());
    wait(jobs, job, &answer)
}

fn status(jobs: &Sender<Job>) -> Result<Status, String> {
    let (reply, answer) = mpsc::channel();
    let reply = reply.into();
    wait(jobs, Job::Status { reply }, &answer)
}

fn wait<T>(jobs: &Sender<Job>, job: Job, answer: &Receiver<T>) -> Result<T, String> {
    jobs.send(job)
        .map_err(|_| "the robot's thread has stopped".to_string())?;
    answer
        .recv_timeout(ANSWER_WAIT)
        .map_err(|_| "the robot's thread did not answer".to_string())
}

/// The task's variables and skills, for completion.
fn refresh(words: &Mutex<Words>, status: &Status) {
    let names = status
        .vars
        .iter()
        .map(|v| v.name.clone())
        .chain(status.skills.iter().cloned());
    match words.lock() {
        Ok(mut w) => w.set_task(names),
        Err(poisoned) => poisoned.into_inner().set_task(names),
    }
}

/// Subscribes to the engine's events and prints notices from them on a thread of
/// their own: through rustyline's printer on a terminal, so that the prompt and the
/// line being typed are redrawn below them; as plain lines otherwise.
fn notices(
    jobs: &Sender<Job>,
    editor: &mut Editor<ShellHelper, FileHistory>,
    terminal: bool,
    watch: Arc<AtomicBool>,
) -> Result<(), String> {
    let (out, events) = mpsc::sync_channel::<String>(EVENT_QUEUE);
    let (done, acknowledged) = mpsc::channel();
    let job = Job::Subscribe {
        conn: SHELL_SUBSCRIBER,
        out: Box::new(out),
        // Nothing to say before the first event.
        first: None,
        done: done.into(),
    };
    wait(jobs, job, &acknowledged)?;
    let mut printer: Box<dyn FnMut(String) + Send> = match terminal {
        true => match editor.create_external_printer() {
            Ok(mut p) => Box::new(move |s| {
                let _ = p.print(format!("{s}\n"));
            }),
            Err(_) => Box::new(|s| println!("{s}")),
        },
        false => Box::new(|s| println!("{s}")),
    };
    std::thread::Builder::new()
        .name("ilmr-shell-notices".into())
        .spawn(move || {
            let mut gate = crate::notice::Gate::default();
            for event in events {
                let Ok(event) = serde_json::from_str::<ilmr_trace::Record<'_>>(&event) else {
                    continue;
                };
                let detail = if watch.load(Ordering::SeqCst) {
                    Detail::Watch
                } else {
                    Detail::Trouble
                };
                if let Some(n) = gate.pass(&event, detail) {
                    printer(n);
                }
            }
        })
        .map_err(|e| format!("cannot start the notice thread: {e}"))?;
    Ok(())
}
