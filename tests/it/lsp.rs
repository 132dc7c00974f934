//! `rigor lsp` spoken to as an editor speaks to it: JSON-RPC with `Content-Length`
//! framing over the built binary's standard input and output. Every wait has a read
//! timeout, so a server that stops answering fails the test instead of hanging it.
//! The fixtures are in `tests/lsp/`.

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::Duration;

/// How long any one answer may take before the test fails.
const PATIENCE: Duration = Duration::from_secs(60);

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/lsp")
}

fn uri(name: &str) -> String {
    format!("file://{}", fixtures().join(name).display())
}

fn fixture(name: &str) -> String {
    std::fs::read_to_string(fixtures().join(name)).expect("fixture")
}

/// A running server and what it has said that no test has taken yet.
struct Server {
    child: Child,
    stdin: ChildStdin,
    inbox: Receiver<Value>,
    unread: Vec<Value>,
    next_id: i64,
}

impl Server {
    /// Starts `rigor lsp` and goes through `initialize`; returns it with the server's
    /// capabilities.
    fn start() -> (Server, Value) {
        let mut child = Command::new(env!("CARGO_BIN_EXE_rigor"))
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("rigor lsp starts");
        let stdin = child.stdin.take().expect("stdin");
        let stdout = child.stdout.take().expect("stdout");
        let (tx, inbox) = channel();
        std::thread::spawn(move || {
            let mut r = BufReader::new(stdout);
            while let Some(msg) = read_message(&mut r) {
                if tx.send(msg).is_err() {
                    break;
                }
            }
        });
        let mut s = Server {
            child,
            stdin,
            inbox,
            unread: Vec::new(),
            next_id: 1,
        };
        let caps = s.request(
            "initialize",
            json!({"processId": null, "rootUri": uri(""), "capabilities": {}}),
        );
        s.notify("initialized", json!({}));
        (s, caps)
    }

    fn send(&mut self, v: Value) {
        let body = v.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).expect("write");
        self.stdin.flush().expect("flush");
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    /// Sends a request and waits for its result.
    fn request(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        self.send(json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        let answer = self.wait(&format!("the answer to {method}"), |m| m["id"] == json!(id));
        assert!(answer.get("error").is_none(), "{method}: {answer}");
        answer["result"].clone()
    }

    /// The first message (taken before any later one) for which `want` holds.
    fn wait(&mut self, what: &str, want: impl Fn(&Value) -> bool) -> Value {
        if let Some(i) = self.unread.iter().position(&want) {
            return self.unread.remove(i);
        }
        loop {
            match self.inbox.recv_timeout(PATIENCE) {
                Ok(m) if want(&m) => return m,
                Ok(m) => self.unread.push(m),
                Err(e) => panic!("waiting for {what}: {e}; had {:?}", self.unread),
            }
        }
    }

    /// The next diagnostics published for `uri`.
    fn diagnostics(&mut self, uri: &str) -> Value {
        self.wait(&format!("diagnostics of {uri}"), |m| {
            m["method"] == "textDocument/publishDiagnostics" && m["params"]["uri"] == uri
        })["params"]
            .clone()
    }

    fn open(&mut self, uri: &str, language: &str, text: &str) {
        let doc = json!({"uri": uri, "languageId": language, "version": 1, "text": text});
        self.notify("textDocument/didOpen", json!({ "textDocument": doc }));
    }

    fn at(&mut self, method: &str, uri: &str, line: u32, character: u32) -> Value {
        let params = json!({
            "textDocument": {"uri": uri},
            "position": {"line": line, "character": character},
        });
        self.request(method, params)
    }

    /// `shutdown`, `exit`, and the server's exit status.
    fn stop(mut self) -> std::process::ExitStatus {
        assert_eq!(self.request("shutdown", Value::Null), Value::Null);
        self.notify("exit", Value::Null);
        for _ in 0..600 {
            if let Some(status) = self.child.try_wait().expect("wait") {
                return status;
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        let _ = self.child.kill();
        panic!("rigor lsp did not exit after `exit`");
    }
}

/// One framed message, or `None` at the end of the stream.
fn read_message(r: &mut impl BufRead) -> Option<Value> {
    let mut length = None;
    loop {
        let mut line = String::new();
        if r.read_line(&mut line).ok()? == 0 {
            return None;
        }
        let line = line.trim_end();
        if line.is_empty() {
            break;
        }
        if let Some(n) = line.strip_prefix("Content-Length: ") {
            length = n.parse::<usize>().ok();
        }
    }
    let mut body = vec![0; length?];
    r.read_exact(&mut body).ok()?;
    serde_json::from_slice(&body).ok()
}

/// The (0-based) lines and codes of the diagnostics of a `publishDiagnostics`.
fn lines_and_codes(p: &Value) -> Vec<(u64, String)> {
    p["diagnostics"]
        .as_array()
        .expect("diagnostics")
        .iter()
        .map(|d| {
            let line = d["range"]["start"]["line"].as_u64().expect("line");
            (line, d["code"].as_str().unwrap_or("").to_string())
        })
        .collect()
}

/// The 0-based line of `text` that starts with `prefix`, and the column of `needle` in it.
fn find(text: &str, prefix: &str, needle: &str) -> (u32, u32) {
    let (n, line) = text
        .lines()
        .enumerate()
        .find(|(_, l)| l.starts_with(prefix))
        .expect("the line is in the fixture");
    let col = line.find(needle).expect("the needle is on the line");
    (n as u32, col as u32)
}

#[test]
fn diagnostics_follow_the_text_and_the_server_exits_cleanly() {
    let (mut s, init) = Server::start();
    let caps = &init["capabilities"];
    for cap in [
        "hoverProvider",
        "definitionProvider",
        "documentSymbolProvider",
        "codeActionProvider",
    ] {
        assert_eq!(caps[cap], json!(true), "{cap} in {init}");
    }
    let (u, text) = (uri("pendulum.deriv"), fixture("pendulum.deriv"));
    s.open(&u, "rigor", &text);
    let p = s.diagnostics(&u);
    let (torque, col) = find(&text, "claim [torque]", "sin(theta) by");
    assert_eq!(
        lines_and_codes(&p),
        vec![(u64::from(torque), "E0301".to_string())],
        "{p}"
    );
    let d = &p["diagnostics"][0];
    assert_eq!(d["severity"], 1, "an error: {d}");
    assert_eq!(d["source"], "rigor");
    assert!(
        d["message"]
            .as_str()
            .unwrap()
            .starts_with("this step does not hold"),
        "{d}"
    );
    // The notes travel as related information: both sides, the counterexample, and the
    // fact used, at the line that states it.
    let related: Vec<&Value> = d["relatedInformation"]
        .as_array()
        .expect("related")
        .iter()
        .collect();
    let said = |w: &str| {
        related
            .iter()
            .any(|r| r["message"].as_str().unwrap().contains(w))
    };
    for w in [
        "1/2 × the right side",
        "left side:",
        "right side:",
        "counterexample: at",
    ] {
        assert!(said(w), "{w} in {related:?}");
    }
    let (moment, _) = find(&text, "given [moment]", "M");
    assert!(
        related
            .iter()
            .any(|r| r["message"] == "[moment]: a fact used"
                && r["location"]["range"]["start"]["line"] == moment),
        "{related:?}"
    );
    // Typing the missing `/2` (an incremental change) fixes the step.
    let at = json!({"line": torque, "character": col - 1});
    let change = json!({"range": {"start": at, "end": at}, "text": "/2"});
    s.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": u, "version": 2}, "contentChanges": [change]}),
    );
    let p = s.diagnostics(&u);
    assert_eq!(p["version"], 2, "{p}");
    assert_eq!(lines_and_codes(&p), vec![], "{p}");
    assert!(s.stop().success());
}

#[test]
fn hovers_and_definitions_reach_across_two_files() {
    let (mut s, _) = Server::start();
    let (lib, main) = (uri("lib.deriv"), uri("pendulum.deriv"));
    let text = fixture("pendulum.deriv");
    s.open(&lib, "rigor", &fixture("lib.deriv"));
    s.open(&main, "rigor", &text);
    s.diagnostics(&main);
    // A label cited: the fact it names, from the file the `use` reads.
    let (line, col) = find(&text, "claim [inertia]", "[IO]");
    let h = s.at("textDocument/hover", &main, line, col + 1);
    let shown = h["contents"]["value"].as_str().expect("markdown");
    assert!(
        shown.contains("claim [IO] m L^2/12 + m (L/2)^2 = m L^2/3"),
        "{shown}"
    );
    assert!(shown.contains("lib.deriv"), "{shown}");
    // …and the same hover on the link shows its verdict and both sides' normal forms.
    assert!(shown.contains("`=` link: verified (identity)"), "{shown}");
    assert!(shown.contains("left side:\n```rigor\nL^2 m/3"), "{shown}");
    assert!(shown.contains("unit: `kg·m²`"), "{shown}");
    // A name: its declaration, what it is, its unit.
    let (line, col) = find(&text, "given [moment]", "theta");
    let shown = s.at("textDocument/hover", &main, line, col + 2)["contents"]["value"].clone();
    let shown = shown.as_str().expect("markdown");
    assert!(
        shown.contains("time theta") && shown.contains("function of time"),
        "{shown}"
    );
    assert!(shown.contains("unit: `rad`"), "{shown}");
    let (line, col) = find(&text, "given [moment]", "g L");
    let shown = s.at("textDocument/hover", &main, line, col)["contents"]["value"].clone();
    assert!(shown.as_str().unwrap().contains("`g > 0`"), "{shown}");
    // A label of this file: the fact it names.
    let (line, col) = find(&text, "claim [torque]", "[moment]");
    let shown = s.at("textDocument/hover", &main, line, col + 2)["contents"]["value"].clone();
    assert!(
        shown
            .as_str()
            .unwrap()
            .contains("given [moment] M = -m g L/2 sin(theta)"),
        "{shown}"
    );
    // Go to definition: a label imported, from its `by` and from its `use`, lands on the
    // claim in the other file; a label of this file, and a name, in this one.
    let (io_line, _) = find(&fixture("lib.deriv"), "claim [IO]", "");
    for (prefix, needle) in [("claim [inertia]", "[IO]"), ("use [IO]", "[IO]")] {
        let (line, col) = find(&text, prefix, needle);
        let loc = s.at("textDocument/definition", &main, line, col + 2);
        assert_eq!(loc["uri"], lib, "{prefix}: {loc}");
        assert_eq!(loc["range"]["start"]["line"], io_line, "{loc}");
    }
    let (line, col) = find(&text, "claim [torque]", "[moment]");
    let loc = s.at("textDocument/definition", &main, line, col + 2);
    assert_eq!(loc["uri"], main);
    assert_eq!(
        loc["range"]["start"]["line"],
        find(&text, "given [moment]", "").0
    );
    let (line, col) = find(&text, "claim [torque]", "g L");
    let loc = s.at("textDocument/definition", &main, line, col);
    assert_eq!(
        loc["range"]["start"]["line"],
        find(&text, "symbols m g L", "").0,
        "{loc}"
    );
    // The outline: the headings, with the statements under them.
    let outline = s.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": main}}),
    );
    let top = &outline[0];
    assert_eq!(top["name"], "A rod swinging about its end", "{outline}");
    let section = &top["children"][0];
    assert_eq!(section["name"], "Moments about the pivot", "{outline}");
    let names: Vec<&str> = section["children"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["[moment]", "[inertia]", "[torque]"], "{outline}");
    assert!(s.stop().success());
}

/// Asks for the fixes of the first diagnostic of `text` (opened as `name`), applies the
/// one whose title holds `title`, and returns the text after it with its diagnostics.
fn fix(s: &mut Server, name: &str, text: &str, title: &str) -> (String, Value) {
    let u = uri(name);
    s.open(&u, "rigor", text);
    let p = s.diagnostics(&u);
    let d = p["diagnostics"][0].clone();
    assert!(d.is_object(), "{name}: a diagnostic: {p}");
    let params = json!({
        "textDocument": {"uri": u},
        "range": d["range"],
        "context": {"diagnostics": [d]},
    });
    let actions = s.request("textDocument/codeAction", params);
    let action = actions
        .as_array()
        .unwrap()
        .iter()
        .find(|a| a["title"].as_str().unwrap().contains(title))
        .unwrap_or_else(|| panic!("{name}: a fix `{title}` in {actions}"))
        .clone();
    let mut edits = action["edit"]["changes"][&u]
        .as_array()
        .expect("edits")
        .clone();
    // Applied from the end, so that earlier offsets stay right.
    edits.sort_by_key(|e| {
        let start = &e["range"]["start"];
        std::cmp::Reverse((start["line"].as_u64(), start["character"].as_u64()))
    });
    let mut fixed = text.to_string();
    for e in edits {
        let at = |p: &Value| {
            let line = p["line"].as_u64().unwrap() as usize;
            let start: usize = fixed.split_inclusive('\n').take(line).map(str::len).sum();
            start + p["character"].as_u64().unwrap() as usize
        };
        let (a, b) = (at(&e["range"]["start"]), at(&e["range"]["end"]));
        fixed.replace_range(a..b, e["newText"].as_str().unwrap());
    }
    let full = json!({"text": fixed});
    s.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": u, "version": 2}, "contentChanges": [full]}),
    );
    let after = s.diagnostics(&u);
    (fixed, after)
}

#[test]
fn quick_fixes_apply_what_the_diagnostics_suggest() {
    let (mut s, _) = Server::start();
    let read = |p: &str| {
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(p)).expect("fixture")
    };
    // A product written without spaces.
    let glued = read("tests/check/fail/dym_glued_product.deriv");
    let (fixed, after) = fix(&mut s, "glued.deriv", &glued, "with `m g d`");
    assert!(fixed.contains("M = -m g d sin(theta) by [M]"), "{fixed}");
    assert_eq!(lines_and_codes(&after), vec![], "{after}");
    // A derivative of a symbol declared constant.
    let prime = read("tests/check/fail/dym_prime_on_constant.deriv");
    let (fixed, after) = fix(
        &mut s,
        "prime.deriv",
        &prime,
        "Declare `theta` with `time theta`",
    );
    assert!(
        fixed.contains("\ntime theta\n") && !fixed.contains("symbols theta"),
        "{fixed}"
    );
    assert_eq!(lines_and_codes(&after), vec![], "{after}");
    // A label mistyped in `by`.
    let label = read("tests/check/fail/kind_by_unknown_label.deriv");
    let (fixed, after) = fix(&mut s, "label.deriv", &label, "with [Fx]");
    assert!(fixed.contains("by [Fx]"), "{fixed}");
    assert_eq!(lines_and_codes(&after), vec![], "{after}");
    // A `use` of a label the imported file does not have: the one it has.
    let text = fixture("pendulum.deriv")
        .replace("use [IO]", "use [I0]")
        .replace("by [IO]", "by [I0]");
    let (fixed, _) = fix(
        &mut s,
        "pendulum_typo.deriv",
        &text,
        "Use [IO], which \"lib.deriv\" has",
    );
    assert!(fixed.contains("use [IO] from"), "{fixed}");
    assert!(s.stop().success());
}

#[test]
fn notes_get_lint_diagnostics_at_their_lines() {
    let (mut s, _) = Server::start();
    let (u, text) = (uri("notes.md"), fixture("notes.md"));
    s.open(&u, "markdown", &text);
    let p = s.diagnostics(&u);
    let (line, _) = find(&text, "I_O =", "");
    assert_eq!(
        lines_and_codes(&p),
        vec![(u64::from(line), "E0301".to_string())],
        "{p}"
    );
    assert_eq!(p["diagnostics"][0]["severity"], 1, "{p}");
    assert!(s.stop().success());
}

/// The order of the messages decides: a document opened after a slow one gets its
/// diagnostics first. Then an edit to the slow one stops its check: the diagnostics
/// that follow are the new version's (its twelve claims would each take the whole time
/// budget of a claim, ten seconds, if the check went on).
#[test]
fn a_slow_document_does_not_hold_up_another() {
    let (mut s, _) = Server::start();
    let (slow, fast) = (uri("slow.deriv"), uri("pendulum.deriv"));
    s.open(&slow, "rigor", &fixture("slow.deriv"));
    s.open(&fast, "rigor", &fixture("pendulum.deriv"));
    let first = s.wait("diagnostics", |m| {
        m["method"] == "textDocument/publishDiagnostics"
    });
    assert_eq!(first["params"]["uri"], fast, "{first}");
    let full = json!({"text": "symbols x > 0\nclaim x + x = 2 x\n"});
    s.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": slow, "version": 2}, "contentChanges": [full]}),
    );
    let p = s.diagnostics(&slow);
    assert_eq!(
        p["version"], 2,
        "the stale version's check was stopped: {p}"
    );
    assert_eq!(lines_and_codes(&p), vec![], "{p}");
    assert!(s.stop().success());
}

/// The VS Code extension's grammar: it names the language's own statement keywords (as
/// `docs/language.md` lists them), the extension points at it, and — where node is
/// installed — the engine VS Code uses compiles every pattern and scopes a sample
/// (`editors/vscode/test/grammar.js`, after `npm ci` if it has not run).
#[test]
fn the_vscode_grammar_compiles_and_scopes_a_derivation() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = root.join("editors/vscode");
    let read = |p: &Path| std::fs::read_to_string(p).expect("readable");
    let grammar: Value =
        serde_json::from_str(&read(&dir.join("syntaxes/deriv.tmLanguage.json"))).expect("JSON");
    assert_eq!(grammar["scopeName"], "source.rigor");
    let package: Value = serde_json::from_str(&read(&dir.join("package.json"))).expect("JSON");
    let contributed = &package["contributes"]["grammars"][0];
    assert_eq!(contributed["scopeName"], "source.rigor");
    assert_eq!(contributed["path"], "./syntaxes/deriv.tmLanguage.json");
    assert_eq!(
        package["contributes"]["languages"][0]["extensions"][0],
        ".deriv"
    );
    // Every statement keyword of the language is one the grammar's statement rules name.
    let language = read(&root.join("docs/language.md"));
    let row = language
        .lines()
        .find(|l| l.starts_with("| a statement |"))
        .expect("the table of lines in docs/language.md");
    let keywords: Vec<&str> = row.split('`').skip(1).step_by(2).collect();
    assert!(keywords.len() >= 12, "{row}");
    let rules = grammar["repository"]["statement"]["patterns"].to_string();
    for k in keywords {
        assert!(
            rules.contains(&format!("|{k}|"))
                || rules.contains(&format!("({k}|"))
                || rules.contains(&format!("|{k})")),
            "`{k}` in {rules}"
        );
    }
    if Command::new("node").arg("--version").output().is_err() {
        eprintln!("skipped: compiling the grammar needs node, which is not installed");
        return;
    }
    if !dir.join("node_modules/vscode-textmate").is_dir() {
        let out = Command::new("npm")
            .args(["ci", "--no-audit", "--no-fund"])
            .current_dir(&dir)
            .output()
            .expect("npm runs");
        assert!(
            out.status.success(),
            "npm ci: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let out = Command::new("node")
        .arg("test/grammar.js")
        .current_dir(&dir)
        .output()
        .expect("node runs");
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && said.contains("scopes as expected"),
        "{said}{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
