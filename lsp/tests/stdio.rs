//! The built server driven over real JSON-RPC on stdio, as an editor drives it: one
//! session from `initialize` to `exit`, each answer snapshotted as JSON with the
//! workspace's path replaced by `ROOT`. Columns are UTF-16: the files use Finnish names.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

use ilmr_compiler::diagnostic::Code;
use serde_json::{Value, json};

// A guard against a server that hangs, not a measure of speed: the deep files' two
// million semantic tokens are 30 MB of JSON, which the unoptimised server and this
// client take 4 s to write and read on an idle machine and over 20 s when the two
// cores are shared with a workspace build.
const TIMEOUT: Duration = Duration::from_secs(60);

struct Server {
    child: Child,
    stdin: ChildStdin,
    messages: Receiver<Value>,
    next_id: i64,
    root_uri: String,
    /// Notifications received while waiting for something else.
    notifications: Vec<Value>,
}

fn read_message(reader: &mut impl BufRead) -> Option<Value> {
    let mut length = None;
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line).ok()? == 0 {
            return None;
        }
        let line = line.trim_end();
        if line.is_empty() {
            break;
        }
        if let Some(v) = line.strip_prefix("Content-Length: ") {
            length = v.parse::<usize>().ok();
        }
    }
    let mut body = vec![0; length?];
    reader.read_exact(&mut body).ok()?;
    // serde_json's default depth limit, as clients built on serde have it.
    let message = serde_json::from_slice(&body);
    Some(message.unwrap_or_else(|e| panic!("the server's message does not parse: {e}")))
}

impl Server {
    fn start(root: &Path) -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ilmr-lsp"))
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("the server starts");
        let stdin = child.stdin.take().expect("piped stdin");
        let stdout = child.stdout.take().expect("piped stdout");
        let (tx, messages) = channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            while let Some(m) = read_message(&mut reader) {
                if tx.send(m).is_err() {
                    break;
                }
            }
        });
        Server {
            child,
            stdin,
            messages,
            next_id: 0,
            root_uri: uri(root, ""),
            notifications: Vec::new(),
        }
    }

    fn send(&mut self, message: Value) {
        let body = message.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).expect("server reads");
        self.stdin.flush().expect("server reads");
    }

    /// Bytes as they are, headers and all.
    fn send_raw(&mut self, bytes: &[u8]) {
        self.stdin.write_all(bytes).expect("server reads");
        self.stdin.flush().expect("server reads");
    }

    /// A body under a correct header, whatever it holds.
    fn send_body(&mut self, body: &[u8]) {
        let mut framed = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
        framed.extend_from_slice(body);
        self.send_raw(&framed);
    }

    /// The next error response that answers no request of the test's.
    fn refusal(&mut self) -> Value {
        loop {
            let m = self.receive();
            if m.get("error").is_some() && m.get("method").is_none() {
                return m;
            }
        }
    }

    /// `initialize` with the folder as the workspace.
    fn initialize(&mut self) -> Value {
        let root = self.root_uri.trim_end_matches('/').to_string();
        let init = self.request(
            "initialize",
            json!({"processId": null, "rootUri": root, "capabilities": {},
                   "workspaceFolders": [{"uri": root, "name": "w"}],
                   "initializationOptions": {"robot": "moro"}}),
        );
        self.notify("initialized", json!({}));
        init
    }

    fn shut_down(mut self) {
        let shutdown = self.request("shutdown", Value::Null);
        assert_eq!(shutdown["result"], Value::Null, "{shutdown}");
        self.notify("exit", Value::Null);
        let status = self.child.wait().expect("the server exits");
        assert!(status.success(), "{status}");
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    /// Sends a request and returns its response, answering the server's own requests
    /// (`client/registerCapability`) and keeping notifications for later.
    fn request(&mut self, method: &str, params: Value) -> Value {
        self.next_id += 1;
        let id = self.next_id;
        self.send(json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        loop {
            let m = self.receive();
            if m.get("id") == Some(&json!(id)) && m.get("method").is_none() {
                return m;
            }
        }
    }

    fn receive(&mut self) -> Value {
        let m = self
            .messages
            .recv_timeout(TIMEOUT)
            .expect("the server answers in time");
        if m.get("method").is_some() && m.get("id").is_some() {
            // A request from the server: accept it, and keep it to be looked at.
            let id = m["id"].clone();
            self.send(json!({"jsonrpc": "2.0", "id": id, "result": null}));
            self.notifications.push(m.clone());
        } else if m.get("method").is_some() {
            self.notifications.push(m.clone());
        }
        m
    }

    /// The next `publishDiagnostics` for `uri`, waiting for it if need be.
    fn diagnostics(&mut self, uri: &str) -> Value {
        loop {
            let found = self.notifications.iter().position(|n| {
                n["method"] == "textDocument/publishDiagnostics" && n["params"]["uri"] == uri
            });
            if let Some(i) = found {
                return self.notifications.remove(i)["params"].clone();
            }
            self.receive();
        }
    }

    /// The response's `result` as JSON text with the workspace's URI made stable.
    fn show(&self, response: &Value) -> String {
        assert!(response.get("error").is_none(), "{response}");
        let text = serde_json::to_string_pretty(&response["result"]).expect("JSON prints");
        text.replace(&self.root_uri, "file:///ROOT/")
    }

    fn show_params(&self, params: &Value) -> String {
        let text = serde_json::to_string_pretty(params).expect("JSON prints");
        text.replace(&self.root_uri, "file:///ROOT/")
    }
}

fn uri(root: &Path, name: &str) -> String {
    let root = root.to_string_lossy();
    format!("file://{}/{name}", root.trim_end_matches('/'))
}

fn workspace(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch workspace");
    dir
}

const TASK: &str = "// Finnish names: columns count UTF-16 units.
käännös = turn(left)
wait(käännös)
ovi_ö = sensor(scanner,door)
wait(ovi_ö)
speed(0.6)
gotoxy(ovi_ö)
KIERROS
";

const SKILLS: &str = "KIERROS:
t1 = turn(d=180,c=1)
wait(t1)
";

/// MoRo's devices with a slow top speed, so that `speed(0.6)` is refused.
const ROBO_INI: &str = "[SENSORSANDACTUATORS]
scanner 1 0 30000 361
battery 6 0 30 1
[OBJECTS]
door 0.8 1.2
[PARAMETERS]
max_speed 0.5
max_curvature 1.333333
[END]
";

fn position(line: u32, character: u32) -> Value {
    json!({"line": line, "character": character})
}

#[test]
fn a_session_over_stdio() {
    let root = workspace("session");
    std::fs::write(root.join("skills.ilms"), SKILLS).unwrap();
    std::fs::write(root.join("ROBO.INI"), ROBO_INI).unwrap();
    let task = uri(&root, "task.ilmr");
    let skills = uri(&root, "skills.ilms");
    let mut s = Server::start(&root);

    let init = s.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": s.root_uri.trim_end_matches('/'),
            "capabilities": {
                "textDocument": {"completion": {"completionItem": {"snippetSupport": true}}}
            },
            "initializationOptions": {"robot": "workpartner"}
        }),
    );
    insta::assert_snapshot!("initialize", s.show(&init));
    s.notify("initialized", json!({}));

    s.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": task, "languageId": "ilmr", "version": 1, "text": TASK}}),
    );
    let opened = s.diagnostics(&task);
    insta::assert_snapshot!("open_diagnostics", s.show_params(&opened));

    // A half-typed line: the diagnostics of the rest of the file stay.
    s.notify(
        "textDocument/didChange",
        json!({
            "textDocument": {"uri": task, "version": 2},
            "contentChanges": [{
                "range": {"start": position(8, 0), "end": position(8, 0)},
                "text": "n = turn("
            }]
        }),
    );
    let changed = s.diagnostics(&task);
    assert_eq!(changed["version"], 2);
    insta::assert_snapshot!("change_diagnostics", s.show_params(&changed));

    let completion = s.request(
        "textDocument/completion",
        json!({"textDocument": {"uri": task}, "position": position(8, 9)}),
    );
    insta::assert_snapshot!("completion_in_turn", s.show(&completion));

    let signature = s.request(
        "textDocument/signatureHelp",
        json!({"textDocument": {"uri": task}, "position": position(8, 9)}),
    );
    insta::assert_snapshot!("signature_in_turn", s.show(&signature));

    // `ovi_ö` on line 7 starts at UTF-16 column 7: `gotoxy(` is seven units.
    let hover = s.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": task}, "position": position(6, 11)}),
    );
    insta::assert_snapshot!("hover_variable", s.show(&hover));

    let definition = s.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": task}, "position": position(7, 3)}),
    );
    insta::assert_snapshot!("definition_skill", s.show(&definition));
    assert!(s.show(&definition).contains("skills.ilms"), "{skills}");

    let references = s.request(
        "textDocument/references",
        json!({
            "textDocument": {"uri": task},
            "position": position(2, 6),
            "context": {"includeDeclaration": true}
        }),
    );
    insta::assert_snapshot!("references_variable", s.show(&references));

    let rename = s.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": task}, "position": position(3, 2), "newName": "ovi_ä"}),
    );
    insta::assert_snapshot!("rename_variable", s.show(&rename));

    let refused = s.request(
        "textDocument/rename",
        json!({"textDocument": {"uri": task}, "position": position(3, 2), "newName": "turn"}),
    );
    assert_eq!(refused["error"]["message"], "`turn` is a command");

    // Finish the half-typed line (in capitals, for the formatter) and add a typo.
    s.notify(
        "textDocument/didChange",
        json!({
            "textDocument": {"uri": task, "version": 3},
            "contentChanges": [{
                "range": {"start": position(8, 9), "end": position(8, 9)},
                "text": "LEFT)\nwait(n)\nfollowwall(lft)\n"
            }]
        }),
    );
    let finished = s.diagnostics(&task);
    assert_eq!(finished["version"], 3);
    let formatting = s.request(
        "textDocument/formatting",
        json!({"textDocument": {"uri": task}, "options": {"tabSize": 4, "insertSpaces": true}}),
    );
    insta::assert_snapshot!("formatting", s.show(&formatting));

    let actions = s.request(
        "textDocument/codeAction",
        json!({
            "textDocument": {"uri": task},
            "range": {"start": position(0, 0), "end": position(12, 0)},
            "context": {"diagnostics": []}
        }),
    );
    insta::assert_snapshot!("code_actions", s.show(&actions));

    // The model file changes on disk: open documents are checked again.
    std::fs::write(
        root.join("ROBO.INI"),
        ROBO_INI.replace("max_speed 0.5", "max_speed 1.0"),
    )
    .unwrap();
    s.notify(
        "workspace/didChangeWatchedFiles",
        json!({"changes": [{"uri": uri(&root, "ROBO.INI"), "type": 2}]}),
    );
    let rechecked = s.diagnostics(&task);
    insta::assert_snapshot!("model_change_diagnostics", s.show_params(&rechecked));

    let shutdown = s.request("shutdown", Value::Null);
    assert_eq!(shutdown["result"], Value::Null);
    s.notify("exit", Value::Null);
    let status = s.child.wait().expect("the server exits");
    assert!(status.success(), "{status}");
}

#[test]
fn without_a_workspace_the_setting_names_the_robot() {
    let root = workspace("no-model");
    let task = uri(&root, "t.ilmr");
    let mut s = Server::start(&root);
    s.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": {},
               "initializationOptions": {"robot": "moro"}}),
    );
    s.notify("initialized", json!({}));
    s.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": task, "languageId": "ilmr", "version": 1,
                                "text": "movemode(wheels)\n"}}),
    );
    let d = s.diagnostics(&task);
    assert_eq!(
        d["diagnostics"][0]["code"], "E0403",
        "MoRo has no movement modes: {d}"
    );
    s.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"ilmr": {"robot": "workpartner"}}}),
    );
    let d = s.diagnostics(&task);
    assert_eq!(d["diagnostics"], json!([]), "Workpartner has them: {d}");
    // Without snippet support, completion inserts plain names.
    let completion = s.request(
        "textDocument/completion",
        json!({"textDocument": {"uri": task}, "position": position(1, 0)}),
    );
    let items = completion["result"]["items"].as_array().expect("a list");
    let turn = items.iter().find(|i| i["label"] == "turn").expect("turn");
    assert_eq!(turn["textEdit"]["newText"], "turn");
    s.request("shutdown", Value::Null);
    s.notify("exit", Value::Null);
    assert!(s.child.wait().expect("exits").success());
}

#[test]
fn the_run_command_says_what_it_cannot_run() {
    let root = workspace("run-refusals");
    std::fs::write(root.join("task.ilmr"), "goahead(1)\n").expect("a task");
    std::fs::write(root.join("skills.ilms"), SKILLS).expect("skills");
    let task = uri(&root, "task.ilmr");
    let mut s = Server::start(&root);
    let root_uri = s.root_uri.trim_end_matches('/').to_string();
    s.request(
        "initialize",
        json!({"processId": null, "rootUri": root_uri,
               "capabilities": {"workspace": {"inlayHint": {"refreshSupport": true},
                                              "codeLens": {"refreshSupport": true}}},
               "initializationOptions": {"robot": "moro", "ilmrc": "/nonexistent/ilmrc"}}),
    );
    s.notify("initialized", json!({}));
    let error = |answer: &Value| answer["error"]["code"].as_i64();
    let unknown = s.request(
        "workspace/executeCommand",
        json!({"command": "ilmr.fly", "arguments": [task]}),
    );
    assert_eq!(error(&unknown), Some(-32602), "{unknown}");
    let bare = s.request("workspace/executeCommand", json!({"command": "ilmr.run"}));
    assert_eq!(error(&bare), Some(-32602), "{bare}");
    let skill = s.request(
        "workspace/executeCommand",
        json!({"command": "ilmr.run", "arguments": [uri(&root, "skills.ilms")]}),
    );
    assert_eq!(error(&skill), Some(-32602), "{skill}");
    assert!(
        skill["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("only a task file")),
        "{skill}"
    );
    // An `ilmrc` that is not there: the run's answer and the message say so, and the
    // client is told to ask for hints and lenses again.
    let run = s.request(
        "workspace/executeCommand",
        json!({"command": "ilmr.run", "arguments": [task]}),
    );
    let summary = run["result"]["summary"].as_str().expect("a summary");
    assert!(
        summary.starts_with("cannot run `/nonexistent/ilmrc`"),
        "{run}"
    );
    assert_eq!(run["result"]["exit"], Value::Null, "{run}");
    let told = |s: &Server, method: &str| s.notifications.iter().any(|n| n["method"] == method);
    assert!(told(&s, "window/showMessage"), "{:?}", s.notifications);
    assert!(
        told(&s, "workspace/inlayHint/refresh"),
        "{:?}",
        s.notifications
    );
    assert!(
        told(&s, "workspace/codeLens/refresh"),
        "{:?}",
        s.notifications
    );
    let lenses = s.request(
        "textDocument/codeLens",
        json!({"textDocument": {"uri": task}}),
    );
    let title = lenses["result"][0]["command"]["title"]
        .as_str()
        .unwrap_or("");
    assert!(title.contains("last run: cannot run"), "{lenses}");
    still_serves(&mut s, "the run command");
    s.shut_down();
}

/// A request that needs the engine, answered normally.
fn still_serves(s: &mut Server, after: &str) {
    let task = uri(Path::new(&s.root_uri["file://".len()..]), "task.ilmr");
    let answer = s.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": task}}),
    );
    assert!(answer.get("error").is_none(), "after {after}: {answer}");
    assert!(answer["result"].is_array(), "after {after}: {answer}");
}

#[test]
fn malformed_messages_are_answered_and_the_server_goes_on() {
    let root = workspace("malformed");
    std::fs::write(root.join("task.ilmr"), "x = 1\nwait(1)\n").unwrap();
    let mut s = Server::start(&root);

    // Even before `initialize`, which every other request must wait for.
    s.send_body(b"{\"jsonrpc\":");
    let r = s.refusal();
    assert_eq!(r["error"]["code"], -32700, "{r}");
    assert_eq!(r["id"], Value::Null, "{r}");
    s.initialize();
    still_serves(&mut s, "a parse error before initialize");

    let parse_errors: [(&str, Vec<u8>); 6] = [
        (
            "invalid UTF-8 in a string",
            b"{\"jsonrpc\":\"2.0\",\"id\":90,\"method\":\"textDocument/hover\",\"params\":\"\xff\xfe\"}"
                .to_vec(),
        ),
        (
            "a lone surrogate",
            br#"{"jsonrpc":"2.0","method":"textDocument/didOpen","params":{"textDocument":{"uri":"file:///x.ilmr","languageId":"ilmr","version":1,"text":"x = \udcff"}}}"#
                .to_vec(),
        ),
        (
            "invalid JSON",
            br#"{"jsonrpc":"2.0","id":91,"method":"shutdown""#.to_vec(),
        ),
        ("an empty body", Vec::new()),
        (
            "JSON nested past serde's limit",
            format!("{}{}", "[".repeat(100_000), "]".repeat(100_000)).into_bytes(),
        ),
        (
            "trailing bytes after the JSON",
            br#"{"jsonrpc":"2.0","method":"initialized","params":{}} {}"#.to_vec(),
        ),
    ];
    for (what, body) in parse_errors {
        s.send_body(&body);
        let r = s.refusal();
        assert_eq!(r["error"]["code"], -32700, "{what}: {r}");
        assert_eq!(r["id"], Value::Null, "{what}: {r}");
        still_serves(&mut s, what);
    }

    let bad_headers: [(&str, &[u8]); 4] = [
        ("a length that is no number", b"Content-Length: twelve\r\n\r\n{\"a\":1}"),
        ("no Content-Length", b"Content-Type: application/json\r\n\r\n{}"),
        (
            "a charset other than UTF-8",
            b"Content-Length: 2\r\nContent-Type: application/vscode-jsonrpc; charset=latin1\r\n\r\n{}",
        ),
        ("a line that is no header", b"hello world\r\n\r\n"),
    ];
    for (what, bytes) in bad_headers {
        s.send_raw(bytes);
        let r = s.refusal();
        assert_eq!(r["error"]["code"], -32700, "{what}: {r}");
        assert_eq!(r["id"], Value::Null, "{what}: {r}");
        still_serves(&mut s, what);
    }

    // A message past the limit is skipped by its length without being kept.
    let limit = ilmr_lsp::framing::MAX_MESSAGE_BYTES;
    s.send_raw(format!("Content-Length: {}\r\n\r\n", limit + 1).as_bytes());
    let chunk = vec![b' '; 1 << 20];
    let mut left = limit + 1;
    while left > 0 {
        let n = left.min(chunk.len());
        s.send_raw(&chunk[..n]);
        left -= n;
    }
    let r = s.refusal();
    assert_eq!(r["error"]["code"], -32700, "{r}");
    assert!(
        r["error"]["message"]
            .as_str()
            .is_some_and(|m| m.contains("longer than the limit")),
        "{r}"
    );
    still_serves(&mut s, "an oversized message");

    // JSON that is not a JSON-RPC message: Invalid Request, with its id when it has one.
    s.send_body(br#"{"jsonrpc":"1.0","id":92,"method":"shutdown"}"#);
    let r = s.refusal();
    assert_eq!(
        (r["error"]["code"].clone(), r["id"].clone()),
        (json!(-32600), json!(92)),
        "{r}"
    );
    still_serves(&mut s, "an invalid request");

    s.shut_down();
}

/// Files nested 1,000,000 deep: the compiler stops at its limits with a diagnostic, and
/// the server neither overflows its stack on them nor walks them for long.
fn deep_files() -> [(&'static str, String, &'static str); 3] {
    const N: usize = 1_000_000;
    let parens = format!("x = {}1{}\nwait(x)\n", "(".repeat(N), ")".repeat(N));
    let sum = format!("x = 1{}\nwait(x)\n", "+1".repeat(N - 1));
    // Unclosed, to stay within the size `ilmrc` reads (8 MiB).
    let ifs = format!("{}wait(1)\n", "if(1)\n".repeat(N));
    [
        ("parens.ilmr", parens, Code::TooComplex.as_str()),
        ("sum.ilmr", sum, Code::TooComplex.as_str()),
        ("ifs.ilmr", ifs, Code::TooDeep.as_str()),
    ]
}

#[test]
fn a_workspace_of_deeply_nested_files_is_served() {
    let root = workspace("deep");
    let files = deep_files();
    for (name, text, _) in &files {
        std::fs::write(root.join(name), text).unwrap();
    }
    // The files are read and checked while the server starts, before any is opened.
    let mut s = Server::start(&root);
    s.initialize();
    for (name, text, code) in files {
        let file = uri(&root, name);
        s.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": file, "languageId": "ilmr", "version": 1, "text": text}}),
        );
        let published = s.diagnostics(&file);
        let codes: Vec<&Value> = published["diagnostics"]
            .as_array()
            .expect("a list")
            .iter()
            .map(|d| &d["code"])
            .collect();
        assert!(codes.contains(&&json!(code)), "{name}: {codes:?}");
        let doc = json!({"textDocument": {"uri": file}});
        let at = json!({"textDocument": {"uri": file}, "position": position(0, 3)});
        let deep = json!({"textDocument": {"uri": file}, "position": position(0, 500_000)});
        for (method, params) in [
            ("textDocument/documentSymbol", doc.clone()),
            ("textDocument/foldingRange", doc.clone()),
            ("textDocument/semanticTokens/full", doc.clone()),
            (
                "textDocument/semanticTokens/range",
                json!({"textDocument": {"uri": file},
                       "range": {"start": position(0, 0), "end": position(40, 0)}}),
            ),
            (
                "textDocument/formatting",
                json!({"textDocument": {"uri": file}, "options": {"tabSize": 4, "insertSpaces": true}}),
            ),
            ("textDocument/hover", at.clone()),
            ("textDocument/completion", deep.clone()),
            ("textDocument/signatureHelp", deep),
            ("textDocument/definition", at.clone()),
            (
                "textDocument/references",
                json!({"textDocument": {"uri": file}, "position": position(0, 0),
                       "context": {"includeDeclaration": true}}),
            ),
        ] {
            let answer = s.request(method, params);
            assert!(answer.get("error").is_none(), "{name} {method}: {answer}");
        }
        s.notify(
            "textDocument/didClose",
            json!({"textDocument": {"uri": file}}),
        );
    }
    s.shut_down();
}

/// A test file (`*.test.toml`) over stdio: every problem `ilmrc test` reports, with its
/// span and code; completion of an assertion's words and of line references; hover on
/// a line reference; re-checked on edits, cleared on close.
#[test]
fn a_test_file_over_stdio() {
    let root = workspace("test_file");
    std::fs::write(
        root.join("task.ilmr"),
        "speed(0.4)\ngoahead(1.2)\nm=goahead(0.7)\nwait(m)\n",
    )
    .unwrap();
    let test = uri(&root, "task.test.toml");
    let text = "task = \"task.ilmr\"\nseed = 1\nworld = \"nowhere.toml\"\n\n[[test]]\nname = \"t\"\nassert = [\"before(line \", \"eventualy: line 9 ends\"]\n";
    let mut s = Server::start(&root);
    s.initialize();
    s.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": test, "languageId": "toml", "version": 1, "text": text}}),
    );
    let published = s.diagnostics(&test);
    let found: Vec<(String, Value, Value)> = published["diagnostics"]
        .as_array()
        .expect("a list")
        .iter()
        .map(|d| {
            let first = d["message"].as_str().unwrap_or("").lines().nth(1);
            (
                d["code"].as_str().unwrap_or("").to_string(),
                d["range"]["start"].clone(),
                json!(first),
            )
        })
        .collect();
    assert_eq!(
        found,
        [
            (
                "A0102".to_string(),
                position(1, 0),
                json!("unknown key `seed`")
            ),
            (
                "A0106".to_string(),
                position(2, 8),
                json!(format!("no file `{}`", root.join("nowhere.toml").display()))
            ),
        ],
        "{published}"
    );
    assert_eq!(published["version"], 1);

    // With the world fixed, the assertions are read: each mistake is said where it is.
    let fixed = text.replace("world = \"nowhere.toml\"", "world = \"empty\"");
    s.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": test, "version": 2},
               "contentChanges": [{"text": fixed}]}),
    );
    let published = s.diagnostics(&test);
    let codes: Vec<(&str, Value)> = published["diagnostics"]
        .as_array()
        .expect("a list")
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap_or(""),
                d["range"]["start"].clone(),
            )
        })
        .collect();
    assert_eq!(
        codes,
        [
            ("A0102", position(1, 0)),
            // An assertion's end is where its text ends, less trailing spaces.
            ("A0201", position(6, 22)),
            ("A0201", position(6, 27)),
        ],
        "{published}"
    );
    assert!(
        published["diagnostics"][2]["message"]
            .as_str()
            .is_some_and(|m| m.ends_with("help: did you mean `eventually`?")),
        "{published}"
    );

    let items = s.request(
        "textDocument/completion",
        json!({"textDocument": {"uri": test}, "position": position(6, 23)}),
    );
    let lines: Vec<(String, String)> = items["result"]["items"]
        .as_array()
        .expect("a list")
        .iter()
        .map(|i| {
            (
                i["label"].as_str().unwrap_or("").to_string(),
                i["detail"].as_str().unwrap_or("").to_string(),
            )
        })
        .collect();
    assert_eq!(
        lines,
        [
            ("1".to_string(), "speed(0.4)".to_string()),
            ("2".to_string(), "goahead(1.2)".to_string()),
            ("3".to_string(), "m=goahead(0.7)".to_string()),
            ("4".to_string(), "wait(m)".to_string()),
        ]
    );
    let words = s.request(
        "textDocument/completion",
        json!({"textDocument": {"uri": test}, "position": position(6, 32)}),
    );
    let first = &words["result"]["items"][0];
    assert_eq!(first["label"], "eventually", "{words}");
    assert_eq!(
        first["textEdit"]["range"],
        json!({"start": position(6, 27), "end": position(6, 32)}),
        "the word being typed is replaced"
    );

    let hover = s.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": test}, "position": position(0, 2)}),
    );
    assert!(
        hover["result"]["contents"]["value"]
            .as_str()
            .is_some_and(|v| v.starts_with("`task`: the task file")),
        "{hover}"
    );

    s.notify(
        "textDocument/didClose",
        json!({"textDocument": {"uri": test}}),
    );
    let cleared = s.diagnostics(&test);
    assert_eq!(cleared["diagnostics"], json!([]));
    s.shut_down();
}
