//! The browser playground in a real browser: `web/build.sh` builds it, a small static
//! server here serves `web/dist`, and headless Chromium, driven through the DevTools
//! protocol by `web/test/drive.js`, opens it and reports what the page shows.
//!
//! The tests need `node`, `npm` and `chromium` (`.ci/run` installs them); without them
//! they fail, unless `RIGOR_SKIP_BROWSER=1`.

use serde_json::Value;
use std::io::{BufRead, BufReader, Write};
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Whether to skip (only when asked, and only without a browser).
fn skip() -> bool {
    let have = |cmd: &str| Command::new(cmd).arg("--version").output().is_ok();
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "chromium".into());
    if have("node") && have("npm") && have(&chromium) {
        return false;
    }
    if std::env::var("RIGOR_SKIP_BROWSER").is_ok_and(|v| v == "1") {
        return true;
    }
    panic!(
        "the browser tests need node, npm and chromium: install them or set RIGOR_SKIP_BROWSER=1"
    );
}

/// Builds the site once and serves it; the base URL.
fn site() -> &'static str {
    static URL: OnceLock<String> = OnceLock::new();
    URL.get_or_init(|| {
        let out = Command::new("bash")
            .arg(root().join("web/build.sh"))
            .output()
            .expect("web/build.sh runs");
        assert!(
            out.status.success(),
            "web/build.sh failed:\n{}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        let dist = root().join("web/dist");
        for f in [
            "index.html",
            "app.js",
            "worker.js",
            "rigor.wasm",
            "examples.json",
        ] {
            assert!(dist.join(f).is_file(), "web/dist/{f} was not built");
        }
        serve(dist)
    })
}

/// A static file server on a free local port, for the rest of the test run.
fn serve(dir: PathBuf) -> String {
    let listener = TcpListener::bind("127.0.0.1:0").expect("a local port");
    let url = format!("http://{}/", listener.local_addr().expect("address"));
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let dir = dir.clone();
            std::thread::spawn(move || respond(stream, &dir));
        }
    });
    url
}

fn respond(mut stream: std::net::TcpStream, dir: &Path) {
    let mut line = String::new();
    let mut reader = BufReader::new(stream.try_clone().expect("clone"));
    if reader.read_line(&mut line).is_err() {
        return;
    }
    // Skip the headers.
    let mut h = String::new();
    while reader.read_line(&mut h).is_ok_and(|n| n > 2) {
        h.clear();
    }
    let path = line.split_whitespace().nth(1).unwrap_or("/");
    let path = path.split(['?', '#']).next().unwrap_or("/");
    let rel = if path == "/" {
        "index.html"
    } else {
        path.trim_start_matches('/')
    };
    let file = dir.join(rel);
    let body = (!rel.contains(".."))
        .then(|| std::fs::read(&file).ok())
        .flatten();
    let kind = match file.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("wasm") => "application/wasm",
        Some("json") => "application/json",
        Some("woff2") => "font/woff2",
        _ => "application/octet-stream",
    };
    let _ = match body {
        Some(b) => stream
            .write_all(
                format!(
                    "HTTP/1.1 200 OK\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                    b.len()
                )
                .as_bytes(),
            )
            .and_then(|_| stream.write_all(&b)),
        None => stream.write_all(
            b"HTTP/1.1 404 Not Found\r\nContent-Length: 0\r\nConnection: close\r\n\r\n",
        ),
    };
}

/// Opens `url` (with `args` for the driver) and returns what the page showed. A long
/// URL goes to the driver in a file (`@FILE`): one argument may hold at most 128 KiB.
fn drive(url: &str, args: &[&str]) -> Value {
    let file = std::env::temp_dir().join(format!(
        "rigor-web-url-{}-{:x}",
        std::process::id(),
        url.len() ^ (url.as_ptr() as usize)
    ));
    let arg = if url.len() > 16_000 {
        std::fs::write(&file, url).expect("write the URL");
        format!("@{}", file.display())
    } else {
        url.to_string()
    };
    let out = Command::new("node")
        .arg(root().join("web/test/drive.js"))
        .arg(&arg)
        .args(args)
        .output()
        .expect("node runs");
    let _ = std::fs::remove_file(&file);
    assert!(
        out.status.success(),
        "the browser driver failed on {}:\n{}",
        &url[..url.len().min(200)],
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("the driver prints JSON")
}

/// `#src=` and the base64url (no padding) of the UTF-8 text.
fn link(text: &str) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
    let b = text.as_bytes();
    let mut out = String::from("#src=");
    for chunk in b.chunks(3) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, &c)| n | (u32::from(c) << (16 - 8 * i)));
        for i in 0..=chunk.len() {
            out.push(A[((n >> (18 - 6 * i)) & 63) as usize] as char);
        }
    }
    out
}

/// The verdict marks: (status, line).
fn marks(v: &Value) -> Vec<(String, u64)> {
    v["marks"]
        .as_array()
        .expect("marks")
        .iter()
        .map(|m| {
            (
                m[0].as_str().unwrap_or("").to_string(),
                m[1].as_u64().unwrap_or(0),
            )
        })
        .collect()
}

const ROD_END: &str = "# The rod about its end
symbols m L > 0
unknowns I_O
use [IG] from \"rod.deriv\"
given [PA] I_O = m L^2/12 + m (L/2)^2
claim [IO] I_O = m L^2/3 by [PA]
claim [bad] I_O = m L^2/4 by [PA]
claim [twice] 2 I_O = 2 m L^2/3 by [IO]
";

#[test]
fn a_shared_link_opens_and_is_checked_at_once() {
    if skip() {
        return;
    }
    let v = drive(&format!("{}{}", site(), link(ROD_END)), &[]);
    assert_eq!(v["status"], "failed", "{v}");
    assert_eq!(
        v["summary"],
        "files: 1, claims: 3, links: 3, verified: 2, failed: 1, undecided: 0, errors: 0"
    );
    // Each link's verdict beside its line; `use … from "rod.deriv"` found the example.
    assert_eq!(
        marks(&v),
        [
            ("verified".into(), 6),
            ("failed".into(), 7),
            ("verified".into(), 8)
        ]
    );
    // The diagnostic with its caret, hint and checked counterexample.
    let diags = v["diagnostics"].as_array().expect("diagnostics");
    assert_eq!(diags.len(), 1, "{diags:?}");
    assert_eq!(diags[0][0], "error");
    assert_eq!(diags[0][1], 7);
    let text = diags[0][2].as_str().unwrap_or("");
    assert!(
        text.starts_with("error[E0301]: this step does not hold"),
        "{text}"
    );
    assert!(
        text.contains("^^^^ the left side is 4/3 × the right side"),
        "{text}"
    );
    assert!(text.contains("= counterexample: at L = "), "{text}");
    // The worked solution, with math set by KaTeX and the failure marked.
    let preview = v["preview"].as_str().unwrap_or("");
    assert!(preview.contains("The rod about its end"), "{preview}");
    assert!(preview.contains("does not hold (line 7)"), "{preview}");
    assert!(v["elements"]["math"].as_u64().unwrap_or(0) > 3, "{v}");
    assert_eq!(v["katexErrors"], serde_json::json!([]), "{v}");
}

#[test]
fn nothing_from_a_shared_link_becomes_markup() {
    if skip() {
        return;
    }
    let hostile = "# <img src=x onerror=\"window.__rigorInjected=1\"> title
symbols m > 0
> <script>window.__rigorInjected = 1</script><iframe src=\"javascript:1\"></iframe> $m$
## <b onmouseover=\"window.__rigorInjected=1\">section</b>
claim [x] m = m by <img src=z onerror=window.__rigorInjected=1>
claim m = 2 m
";
    let v = drive(&format!("{}{}", site(), link(hostile)), &[]);
    no_markup(&v);
    let preview = v["preview"].as_str().unwrap_or("");
    assert!(preview.contains("<img src=x onerror="), "{preview}");
    assert!(
        preview.contains("<script>window.__rigorInjected = 1</script>"),
        "{preview}"
    );
    assert!(preview.contains("<b onmouseover="), "{preview}");
    assert!(marks(&v).contains(&("failed".into(), 6)), "{v}");
    // A file that cannot be read: its listing is text too.
    let broken = "symbols m > 0\nclaim [<img src=x onerror=window.__rigorInjected=1>] m = m\n";
    let v = drive(&format!("{}{}", site(), link(broken)), &[]);
    no_markup(&v);
    let preview = v["preview"].as_str().unwrap_or("");
    assert!(preview.contains("claim [<img src=x onerror="), "{preview}");
    assert_eq!(marks(&v), [("error".into(), 2)], "{v}");
}

/// No script from the file ran, and it made no element of its own.
fn no_markup(v: &Value) {
    assert_eq!(v["scriptRan"], false, "{v}");
    for tag in ["img", "script", "iframe", "b"] {
        assert!(v["elements"].get(tag).is_none(), "a <{tag}> element: {v}");
    }
}

#[test]
fn typing_rechecks_and_keeps_the_text_in_the_link() {
    if skip() {
        return;
    }
    let typed = "symbols m L > 0\nclaim [IO] m L^2/12 + m (L/2)^2 = m L^2/3\nclaim [no] m L^2/12 = m L^2/3\n";
    let v = drive(site(), &["--type", typed]);
    assert_eq!(
        marks(&v),
        [("verified".into(), 2), ("failed".into(), 3)],
        "{v}"
    );
    assert_eq!(v["hash"], link(typed), "{v}");
    // A syntax error is an error beside its line, not a verdict on a link.
    let v = drive(site(), &["--type", "symbols m > 0\nclaim m = (m\n"]);
    assert_eq!(v["status"], "failed", "{v}");
    assert_eq!(marks(&v), [("error".into(), 2)], "{v}");
}

#[test]
fn every_example_is_one_click_away_and_verifies() {
    if skip() {
        return;
    }
    let mut files: Vec<String> = std::fs::read_dir(root().join("derivations"))
        .expect("derivations/")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".deriv"))
        .collect();
    files.sort();
    let v = drive(site(), &["--examples"]);
    let shown: Vec<&str> = v["examples"]
        .as_array()
        .expect("examples")
        .iter()
        .map(|e| e[0].as_str().unwrap_or(""))
        .collect();
    assert_eq!(shown, files);
    for e in v["examples"].as_array().expect("examples") {
        assert_eq!(e[1], "ok", "{e}");
        // Every formula of the worked solution typesets (no KaTeX error).
        assert_eq!(e[3], serde_json::json!([]), "{e}");
        assert!(
            e[2].as_str()
                .unwrap_or("")
                .contains("failed: 0, undecided: 0, errors: 0"),
            "{e}"
        );
    }
}

#[test]
fn a_derivation_that_runs_long_is_stopped_by_the_budget() {
    if skip() {
        return;
    }
    // Integrating (x - 1)^6000 writes the power out, which runs past the page's budget
    // of 3 s per claim: the claim is undecided, the page answers, and the next claim is
    // still checked.
    let slow = "symbols x\nclaim int((x - 1)^6000, x, 0, 2) = 2/6001\nclaim x + x = 2 x\n";
    let v = drive(&format!("{}{}", site(), link(slow)), &[]);
    assert_eq!(
        marks(&v),
        [("undecided".into(), 2), ("verified".into(), 3)],
        "{v}"
    );
    let diags = v["diagnostics"].as_array().expect("diagnostics");
    assert!(
        diags
            .iter()
            .any(|d| d[2].as_str().unwrap_or("").contains("E0902")),
        "{diags:?}"
    );
}

#[test]
fn a_link_that_cannot_be_read_says_so_and_claims_nothing() {
    if skip() {
        return;
    }
    // `__4` is the bytes FF FE: not UTF-8. `%%` is not base64url at all.
    for hash in ["#src=__4", "#src=%25%25"] {
        let v = drive(&format!("{}{hash}", site()), &[]);
        assert_eq!(v["status"], "error", "{hash}: {v}");
        let text = v["statusText"].as_str().unwrap_or("");
        assert!(text.contains("this link cannot be read"), "{hash}: {text}");
        assert!(!text.contains("verified"), "{hash}: {text}");
        assert_eq!(marks(&v), [], "{hash}: {v}");
        assert_eq!(v["summary"], "", "{hash}: {v}");
        assert_eq!(v["preview"], "", "{hash}: {v}");
        assert_eq!(v["editorLength"], 0, "{hash}: {v}");
    }
}

#[test]
fn an_empty_document_has_nothing_to_check_and_verifies_nothing() {
    if skip() {
        return;
    }
    for text in ["", "# Only a title\nsymbols m > 0\n"] {
        let v = drive(&format!("{}{}", site(), link(text)), &[]);
        assert_eq!(v["status"], "empty", "{text:?}: {v}");
        let status = v["statusText"].as_str().unwrap_or("");
        assert!(status.starts_with("nothing to check"), "{text:?}: {status}");
        assert!(!status.contains("all steps verified"), "{text:?}: {status}");
    }
    // One step, verified: said as it is.
    let v = drive(
        &format!("{}{}", site(), link("symbols x\nclaim x + x = 2 x\n")),
        &[],
    );
    assert_eq!(v["status"], "ok", "{v}");
    assert!(
        v["statusText"]
            .as_str()
            .unwrap_or("")
            .starts_with("the one step verified"),
        "{v}"
    );
}

#[test]
fn a_large_document_is_shown_in_slices_and_the_page_stays_responsive() {
    if skip() {
        return;
    }
    // 10,000 short claims: typesetting them all blocked the page for about 43 s.
    let mut text = String::from("symbols x\n");
    for k in 1..=10_000 {
        text.push_str(&format!("claim x + {k} = {k} + x\n"));
    }
    let v = drive(
        &format!("{}{}", site(), link(&text)),
        &["--timeout", "150000"],
    );
    assert_eq!(v["status"], "ok", "{}", short(&v));
    assert!(
        v["statusText"]
            .as_str()
            .unwrap_or("")
            .starts_with("all 10000 steps verified"),
        "{}",
        short(&v)
    );
    assert_eq!(marks(&v).len(), 10_000);
    // The preview is cut, and says so.
    assert_eq!(v["cuts"], serde_json::json!(["blocks"]), "{}", short(&v));
    let preview = v["preview"].as_str().unwrap_or("");
    assert!(
        preview.contains("The worked solution is cut here"),
        "{}",
        short(&v)
    );
    // The page answered every poll promptly while it checked and built itself (the
    // worker checks; the page is built in slices).
    let slowest = v["slowestPoll"].as_u64().unwrap_or(u64::MAX);
    assert!(
        slowest < 2_000,
        "the page was blocked for {slowest} ms: {}",
        short(&v)
    );
}

/// A snapshot without its long parts, for failure messages.
fn short(v: &Value) -> String {
    let mut v = v.clone();
    for k in ["marks", "preview", "diagnostics"] {
        if let Some(x) = v.get_mut(k) {
            let s = x.to_string();
            *x = Value::String(s.chars().take(400).collect());
        }
    }
    v.to_string()
}
