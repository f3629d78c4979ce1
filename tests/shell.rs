//! `ilmrc shell` driven as a person would: through a pseudo-terminal (Python's `pty`
//! module relays between the test's pipes and a terminal the shell owns, so line
//! editing, completion and history are rustyline's real ones) and with piped stdin
//! (no terminal: plain lines). The robot runs in real time, so every expectation waits
//! for its text up to a deadline rather than for a fixed time.

use std::io::{Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Every wait in these tests ends by this deadline.
const PATIENCE: Duration = Duration::from_secs(20);

/// Gives the shell a terminal of 120 x 40 on a pty, copies this process's stdin to it
/// and what the shell writes to stdout, and exits with the shell's exit code.
const PTY_RELAY: &str = r#"
import fcntl, os, pty, select, struct, subprocess, sys, termios
master, slave = pty.openpty()
fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 120, 0, 0))
shell = subprocess.Popen(sys.argv[1:], stdin=slave, stdout=slave, stderr=slave,
                         start_new_session=True, close_fds=True)
os.close(slave)
inputs = [master, 0]
while True:
    ready, _, _ = select.select(inputs, [], [], 0.1)
    if master in ready:
        try:
            data = os.read(master, 4096)
        except OSError:
            data = b""
        if not data:
            break
        os.write(1, data)
    if 0 in ready:
        data = os.read(0, 4096)
        if data:
            os.write(master, data)
        else:
            inputs.remove(0)
sys.exit(shell.wait())
"#;

/// A running shell, killed when dropped.
struct Shell {
    child: Child,
    stdin: Option<ChildStdin>,
    /// Everything the shell printed so far (stdout and stderr), escapes removed.
    seen: Arc<Mutex<String>>,
    /// How far `expect` has read in `seen`.
    cursor: usize,
}

impl Shell {
    fn piped(args: &[&str]) -> Shell {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_ilmrc"));
        cmd.arg("shell").args(args);
        Shell::spawn(cmd, true)
    }

    fn on_terminal(args: &[&str]) -> Shell {
        let mut cmd = Command::new("python3");
        cmd.args(["-c", PTY_RELAY, env!("CARGO_BIN_EXE_ilmrc"), "shell"])
            .args(args)
            .env("TERM", "xterm");
        Shell::spawn(cmd, false)
    }

    fn spawn(mut cmd: Command, pipe_stderr: bool) -> Shell {
        cmd.current_dir(env!("CARGO_MANIFEST_DIR"))
            .env("NO_COLOR", "1")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(if pipe_stderr {
                Stdio::piped()
            } else {
                Stdio::inherit()
            });
        let mut child = cmd.spawn().expect("start the shell");
        let seen = Arc::new(Mutex::new(String::new()));
        let mut sources: Vec<Box<dyn Read + Send>> =
            vec![Box::new(child.stdout.take().expect("piped stdout"))];
        if let Some(err) = child.stderr.take() {
            sources.push(Box::new(err));
        }
        for mut source in sources {
            let seen = Arc::clone(&seen);
            std::thread::spawn(move || {
                let mut buf = [0u8; 4096];
                while let Ok(n) = source.read(&mut buf) {
                    if n == 0 {
                        return;
                    }
                    let text = String::from_utf8_lossy(&buf[..n]).into_owned();
                    seen.lock().expect("output lock").push_str(&text);
                }
            });
        }
        Shell {
            stdin: child.stdin.take(),
            child,
            seen,
            cursor: 0,
        }
    }

    /// Sends raw bytes, which need not be UTF-8.
    fn bytes(&mut self, bytes: &[u8]) {
        let stdin = self.stdin.as_mut().expect("stdin open");
        stdin.write_all(bytes).expect("send bytes");
        stdin.flush().expect("flush bytes");
    }

    /// Sends keys as typed (a terminal wants `\r` for Enter, a pipe `\n`).
    fn keys(&mut self, keys: &str) {
        let stdin = self.stdin.as_mut().expect("stdin open");
        stdin.write_all(keys.as_bytes()).expect("send keys");
        stdin.flush().expect("flush keys");
    }

    /// Waits until `text` appears after what earlier expectations consumed; returns
    /// everything up to and including it (escapes and carriage returns removed).
    fn expect(&mut self, text: &str) -> String {
        let deadline = Instant::now() + PATIENCE;
        loop {
            let plain = plain(&self.seen.lock().expect("output lock"));
            if let Some(at) = plain.get(self.cursor..).and_then(|rest| rest.find(text)) {
                let end = self.cursor + at + text.len();
                let got = plain[self.cursor..end].to_string();
                self.cursor = end;
                return got;
            }
            if Instant::now() > deadline {
                panic!(
                    "`{text}` did not appear; after the last expectation the shell printed:\n{}",
                    plain.get(self.cursor..).unwrap_or("")
                );
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Closes stdin and waits for the exit code.
    fn exit_code(&mut self) -> Option<i32> {
        drop(self.stdin.take());
        let deadline = Instant::now() + PATIENCE;
        loop {
            if let Some(status) = self.child.try_wait().expect("wait for the shell") {
                return status.code();
            }
            if Instant::now() > deadline {
                panic!("the shell did not exit");
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

impl Drop for Shell {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Terminal output as text: CSI escape sequences and carriage returns removed.
fn plain(raw: &str) -> String {
    let mut out = String::with_capacity(raw.len());
    let mut chars = raw.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\u{1b}' => {
                if chars.peek() == Some(&'[') {
                    chars.next();
                    // Parameters, then one final byte in @..~.
                    for d in chars.by_ref() {
                        if ('@'..='~').contains(&d) {
                            break;
                        }
                    }
                } else {
                    chars.next();
                }
            }
            '\r' => {}
            c => out.push(c),
        }
    }
    out
}

/// The number after `key` in a status view, e.g. `speed` in "speed 0.3 m/s".
fn number_after(view: &str, key: &str) -> f64 {
    let rest = view
        .rsplit_once(key)
        .unwrap_or_else(|| panic!("no `{key}` in {view}"))
        .1;
    rest.split_whitespace()
        .next()
        .and_then(|w| w.trim_end_matches(',').parse().ok())
        .unwrap_or_else(|| panic!("no number after `{key}` in {view}"))
}

/// The status view from its pose on, read through the empty line that ends it.
fn status(shell: &mut Shell, enter: &str) -> String {
    shell.keys(&format!(":status{enter}"));
    shell.expect("pose x");
    let view = format!("pose x{}", shell.expect("\n\n"));
    assert!(view.contains("\nvariables"), "{view}");
    view
}

/// Polls the status view until `done` holds for it.
fn status_until(shell: &mut Shell, what: &str, done: impl Fn(&str) -> bool) -> String {
    let deadline = Instant::now() + PATIENCE;
    loop {
        let view = status(shell, "\n");
        if done(&view) {
            return view;
        }
        assert!(Instant::now() < deadline, "{what}: {view}");
        std::thread::sleep(Duration::from_millis(100));
    }
}

#[test]
fn piped_lines_join_are_rejected_checked_stopped_and_resumed() {
    let mut sh = Shell::piped(&["--robot", "moro", "--world", "office"]);
    sh.expect("ILMR shell: moro in office");

    sh.keys("m = goahead(3)\n");
    sh.expect("joined at t=");

    sh.keys("goahed(1)\n");
    let rejected = sh.expect("not joined");
    assert!(rejected.contains("[E0301]"), "{rejected}");
    assert!(rejected.contains("did you mean `goahead`?"), "{rejected}");

    // A warning does not stop a line: it joins and the warning is shown.
    sh.keys("turn(d=90,c=2)\n");
    let warned = sh.expect("joined at t=");
    assert!(warned.contains("[W0405]"), "{warned}");

    sh.keys("check\nspeed(0.3)\ngoahed(2)\nwait(m)\ncheckend\n");
    let checked = sh.expect("nothing joined");
    assert!(checked.contains("<line>:2:1"), "{checked}");
    assert!(
        checked.contains("check: 3 line(s), 1 error(s); nothing joined"),
        "{checked}"
    );
    sh.keys("check\nwait(m)\ncheckend\n");
    sh.expect("check: 1 line(s), no errors, 0 warning(s); nothing joined");

    let moving = status_until(&mut sh, "the robot did not get going", |v| {
        number_after(v, "speed") > 0.1
    });
    assert!(moving.contains("<typed 1>:1  m = goahead(3)"), "{moving}");
    assert!(moving.contains("m  status 0"), "{moving}");

    sh.keys("stop\n");
    sh.expect("joined at t=");
    let halted = status_until(&mut sh, "the robot did not stop", |v| {
        number_after(v, "speed") == 0.0
    });
    // Stopped, not ended: the movement is still live, waiting for `cont`.
    assert!(halted.contains("goahead(3)"), "{halted}");
    let x_stopped = number_after(&halted, "pose x");
    std::thread::sleep(Duration::from_millis(500));
    let still = status(&mut sh, "\n");
    assert!(
        (number_after(&still, "pose x") - x_stopped).abs() < 0.01,
        "the robot crept while stopped: {halted} then {still}"
    );

    sh.keys("cont\n");
    sh.expect("joined at t=");
    status_until(&mut sh, "the robot did not go on", |v| {
        number_after(v, "pose x") > x_stopped + 0.05
    });

    sh.keys("exit\n");
    sh.expect("left the shell at t=");
    assert_eq!(sh.exit_code(), Some(0));
}

#[test]
fn a_refusal_is_told_above_the_prompt_with_its_code_and_way_out() {
    let mut sh = Shell::piped(&["--robot", "moro", "--world", "office"]);
    sh.expect("ILMR shell: moro in office");
    // Half a metre to the side: no path the robot can turn gets there.
    sh.keys("gotoxy(8.1,5.5)\n");
    let told = sh.expect("way out: give a heading the robot can reach");
    assert!(
        told.contains("refused `gotoxy(8.1,5.5)`")
            && told.contains("R0110): the path needs curvature"),
        "{told}"
    );
    sh.keys("exit\n");
    sh.expect("left the shell at t=");
}

#[test]
fn blocks_are_collected_until_they_close() {
    let mut sh = Shell::piped(&[]);
    sh.keys("n = 0\nwhile(n < 3)\n  n = n + 1\nendwhile\n");
    sh.expect("joined at t=");
    sh.expect("joined 3 lines at t=");
    status_until(&mut sh, "the loop did not count", |v| {
        v.contains("n  status 1, value 3")
    });
    sh.keys(":nonsense\ncheckend\n");
    sh.expect("unknown shell command `:nonsense`");
    sh.expect("`checkend` without `check`");
    // End of input leaves the shell as :quit does.
    assert_eq!(sh.exit_code(), Some(0));
    sh.expect("left the shell");
}

#[test]
fn a_terminal_gets_completion_history_and_the_same_answers() {
    let dir = std::env::temp_dir().join(format!("ilmr-shell-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let history = dir.join("history");
    let history_arg = history.display().to_string();
    let mut sh = Shell::on_terminal(&["--history", &history_arg]);
    sh.expect("ILMR shell: moro");
    sh.expect("ilmr> ");

    // Tab twice lists what `goa` can start (a command and a keyword); one more letter
    // and Tab completes the command: the line joins (as `goah(0.5)` would not) and is
    // kept in the history as completed.
    sh.keys("goa\t\t");
    sh.expect("goahead");
    sh.expect("goalpos");
    sh.keys("h\t");
    std::thread::sleep(Duration::from_millis(200));
    sh.keys("(0.5)\r");
    let joined = sh.expect("joined at t=");
    assert!(!joined.contains("E0301"), "{joined}");

    sh.keys("goahed(1)\r");
    let rejected = sh.expect("not joined");
    assert!(rejected.contains("[E0301]"), "{rejected}");

    // Up twice brings back the good line.
    sh.keys("\u{1b}[A\u{1b}[A\r");
    sh.expect("joined at t=");

    // Typed ahead, as fast as a paste: every line is kept for the next prompt.
    sh.keys("check\rgoahed(2)\rcheckend\r");
    sh.expect("check: 1 line(s), 1 error(s); nothing joined");

    // A pasted block (bracketed paste) arrives as one input of several lines.
    sh.keys("\u{1b}[200~if(1 < 2)\n  pasted = 3\nendif\u{1b}[201~\r");
    sh.expect("joined 3 lines at t=");

    // Ctrl-C drops a block being typed.
    sh.keys("if(1 < 2)\r");
    sh.expect("...> ");
    sh.keys("\u{3}");
    sh.expect("dropped the unfinished block");

    let view = status(&mut sh, "\r");
    assert!(view.contains("pasted  status 1, value 3"), "{view}");
    assert!(number_after(&view, "pose x") > 4.0, "{view}");

    sh.keys(":quit\r");
    sh.expect("left the shell at t=");
    assert_eq!(sh.exit_code(), Some(0));
    let kept = std::fs::read_to_string(&history).expect("the history file is written");
    let _ = std::fs::remove_dir_all(&dir);
    assert!(kept.contains("goahead(0.5)"), "{kept}");
    assert!(kept.contains(":quit"), "{kept}");
}

#[test]
fn a_bad_task_or_robot_exits_before_the_prompt() {
    let dir = std::env::temp_dir().join(format!("ilmr-shell-task-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bad = dir.join("bad.ilmr");
    std::fs::write(&bad, "goahed(1)\n").expect("write task");
    let bad_arg = bad.display().to_string();

    let mut sh = Shell::piped(&["--task", &bad_arg]);
    let out = sh.expect("E0301");
    assert!(!out.contains("ILMR shell"), "{out}");
    assert_eq!(sh.exit_code(), Some(1));

    let mut sh = Shell::piped(&["--robot", "rover"]);
    sh.expect("error:");
    assert_eq!(sh.exit_code(), Some(2));

    let good = dir.join("good.ilmr");
    std::fs::write(&good, "m = goahead(0.5)\n").expect("write task");
    let good_arg = good.display().to_string();
    let mut sh = Shell::piped(&["--task", &good_arg]);
    // The task's variable is there for lines to use.
    sh.keys("wait(m)\n");
    sh.expect("joined at t=");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--task` takes what `ilmrc build` wrote as it takes the task's text.
#[test]
fn a_built_task_is_loaded_like_its_text() {
    let dir = std::env::temp_dir().join(format!("ilmr-shell-ilmb-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let task = dir.join("good.ilmr");
    std::fs::write(&task, "m = goahead(0.5)\n").expect("write task");
    let built = dir.join("good.ilmb");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_ilmrc"))
        .args(["build", "-o"])
        .args([&built, &task])
        .output()
        .expect("ilmrc build");
    assert!(status.status.success(), "{status:?}");
    let built_arg = built.display().to_string();
    let mut sh = Shell::piped(&["--task", &built_arg]);
    sh.keys("wait(m)\n");
    sh.expect("joined at t=");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_piped_line_that_is_not_utf8_or_too_long_is_skipped_and_reading_goes_on() {
    let mut sh = Shell::piped(&[]);
    sh.expect("ILMR shell");
    sh.bytes(b"n = 1\ngo\xffahead(1)\n");
    sh.expect("joined at t=");
    sh.expect("error: line 2 is not UTF-8 (invalid byte at column 3); skipped");
    // Three mebibytes on one line: far above the limit, held a buffer at a time.
    let mut long = b"x = ".to_vec();
    long.extend(std::iter::repeat_n(b'(', 3 << 20));
    long.push(b'\n');
    sh.bytes(&long);
    sh.expect("error: line 3 is longer than");
    sh.expect("bytes (MAX_LINE_BYTES); skipped");
    // A block that lost a line is dropped, not joined without it.
    sh.bytes(b"while(n < 3)\n\xfe\nn = 5\n");
    sh.expect("error: line 5 is not UTF-8 (invalid byte at column 1); skipped, and the unfinished block was dropped");
    sh.expect("joined at t=");
    status_until(&mut sh, "the line after the bad ones did not run", |v| {
        v.contains("n  status 1, value 5")
    });
    sh.keys("exit\n");
    sh.expect("left the shell at t=");
    assert_eq!(sh.exit_code(), Some(0));
}

#[test]
fn a_line_nested_past_the_limits_is_an_error_and_the_shell_reads_on() {
    let mut sh = Shell::piped(&[]);
    sh.expect("ILMR shell");
    let parens = |n: usize| format!("x = {}1{}\n", "(".repeat(n), ")".repeat(n));
    let plus = |n: usize| format!("x = 1{}\n", "+1".repeat(n - 1));
    // Under the 1 MiB line limit: the compiler's depth limit answers.
    for line in [parens(3_000), parens(400_000), plus(400_000)] {
        sh.keys(&line);
        let answer = sh.expect("not joined");
        assert!(answer.contains("[E0104]"), "{answer}");
        sh.keys("k = 1\n");
        sh.expect("joined at t=");
    }
    // 3,000 nested `if` blocks, typed a line at a time.
    let ifs = format!(
        "n = 1\n{}n = 2\n{}",
        "if(n>0)\n".repeat(3_000),
        "endif\n".repeat(3_000)
    );
    sh.keys(&ifs);
    sh.expect("joined at t=");
    let answer = sh.expect("not joined");
    assert!(answer.contains("[E0210]"), "{answer}");
    // Over it: skipped before the compiler.
    for line in [parens(1_000_000), plus(1_000_000)] {
        sh.keys(&line);
        sh.expect("bytes (MAX_LINE_BYTES); skipped");
    }
    sh.keys("k = 7\n");
    status_until(&mut sh, "the shell stopped reading", |v| {
        v.contains("k  status 1, value 7")
    });
    sh.keys("exit\n");
    sh.expect("left the shell at t=");
    assert_eq!(sh.exit_code(), Some(0));
}

/// The skills of `--skills DIR` that a shell's lines may call, one with parameters
/// (issue 17 item 6); the task calls only one specialization of it.
const PARAM_SKILLS: &str = "Corner(d, side=left/right):\nspeed(0.3)\nm = goahead(d)\nwait(m)\nturn(side)\n\nPlain:\nspeed(0.2)\n\nFast(v):\nspeed(v)\n";

/// A line may call any loaded skill, a parameterized one with arguments the task never
/// gave (the running module holds only the task's specializations): it is checked,
/// joined and run; a bad argument gets the diagnostic a task file gets from `check`.
#[test]
fn a_line_calls_a_parameterized_skill_with_new_arguments() {
    let dir = std::env::temp_dir().join(format!("ilmr-shell-params-{}", std::process::id()));
    let skills = dir.join("skills");
    std::fs::create_dir_all(&skills).expect("temp dir");
    std::fs::write(skills.join("corner.ilms"), PARAM_SKILLS).expect("write skills");
    let task = dir.join("task.ilmr");
    std::fs::write(&task, "Corner(0.5, left)\n").expect("write task");
    // What `ilmrc check` says of the same calls in a task file.
    let in_a_file = |line: &str| {
        let file = dir.join("calls.ilmr");
        std::fs::write(&file, format!("{line}\n")).expect("write task");
        let out = Command::new(env!("CARGO_BIN_EXE_ilmrc"))
            .args(["check", "--skills"])
            .args([&skills, &file])
            .output()
            .expect("ilmrc check");
        assert_eq!(out.status.code(), Some(1), "{out:?}");
        let text = String::from_utf8_lossy(&out.stdout).to_string();
        text.lines()
            .find(|l| l.contains("] Error: "))
            .map(plain)
            .expect("an error")
    };
    let (task_arg, skills_arg) = (task.display().to_string(), skills.display().to_string());
    let mut sh = Shell::piped(&["--task", &task_arg, "--skills", &skills_arg]);
    sh.expect("ILMR shell: moro");

    sh.keys("Corner(1.5, right)\n");
    sh.expect("joined at t=");
    let live = status_until(&mut sh, "the new specialization did not run", |v| {
        v.contains("<typed 1>:1  Corner(1.5, right)")
    });
    assert!(live.contains("corner.ilms:3  m = goahead(d)"), "{live}");
    // A plain skill the task never called joins too.
    sh.keys("Plain\n");
    sh.expect("joined at t=");

    for (line, code) in [
        ("Corner(2, up)", "E0304"),
        ("Corner(2)", "E0302"),
        ("Fast(2)", "E0404"),
    ] {
        sh.keys(&format!("{line}\n"));
        let rejected = plain(&sh.expect("not joined"));
        assert!(
            rejected.contains(&format!("[{code}]")),
            "{line}: {rejected}"
        );
        let said = in_a_file(line);
        assert!(
            rejected.contains(said.trim()),
            "{line}: `{said}` in {rejected}"
        );
    }
    // The speed beyond the limit stands in the skill: the line says where.
    sh.keys("Fast(2)\n");
    let rejected = plain(&sh.expect("not joined"));
    assert!(rejected.contains("corner.ilms:11:7"), "{rejected}");
    sh.keys("Fast(0.2)\n");
    sh.expect("joined at t=");

    sh.keys("exit\n");
    sh.expect("left the shell at t=");
    assert_eq!(sh.exit_code(), Some(0));
    let _ = std::fs::remove_dir_all(&dir);
}
