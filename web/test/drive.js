// Drives a real headless Chromium through the DevTools protocol (over a pipe: no
// extra packages) for rigor's browser tests: opens URL, waits until the page has
// finished checking (#status data-kind is ok, failed, error or empty), optionally types new
// text into the editor and waits again, then prints what the page shows as JSON.
//
//   node web/test/drive.js URL|@FILE [--type TEXT] [--examples] [--screenshot OUT.png]
//                              [--timeout MS]
//
// With --examples it clicks every example button in turn, waits for its check and
// records [name, status, summary, [KaTeX errors in the preview]] in "examples".
// Output: {"status": kind, "statusText", "summary", "marks": [[status, line, detail]],
//          "diagnostics": [[severity, line, text]], "preview": text,
//          "elements": {tag: count} (of the preview), "scriptRan": bool, "hash",
//          "exampleNames": [name], "katexErrors": [message],
//          "cuts": [what the page left out: "blocks", "diagnostics", "deadline"],
//          "editorLength", "longestTask" (ms, the page's longest main-thread task),
//          "slowestPoll" (ms, the longest the page took to answer a poll while it
//          checked and built itself),
//          "examples": [[name, status, summary, [KaTeX error]]]}
"use strict";
const { spawn } = require("child_process");
const fs = require("fs");
const os = require("os");
const path = require("path");

const args = process.argv.slice(2);
// `@FILE`: the URL is in FILE (a long `#src=` link is longer than one argument may be).
const url = args[0].startsWith("@") ? fs.readFileSync(args[0].slice(1), "utf8").trim() : args[0];
const opt = (name) => {
  const i = args.indexOf(name);
  return i > 0 ? args[i + 1] : null;
};
const timeoutMs = Number(opt("--timeout") || 30000);
const browser = process.env.CHROMIUM || "chromium";

const profile = fs.mkdtempSync(path.join(os.tmpdir(), "rigor-chromium-"));
const chrome = spawn(
  browser,
  [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--no-first-run",
    "--disable-extensions",
    "--remote-debugging-pipe",
    "--window-size=1400,1000",
    `--user-data-dir=${profile}`,
    "about:blank",
  ],
  { stdio: ["ignore", "ignore", "ignore", "pipe", "pipe"] },
);
const toChrome = chrome.stdio[3];
const fromChrome = chrome.stdio[4];

let nextId = 0;
const waiting = new Map();
let buffer = Buffer.alloc(0);
fromChrome.on("data", (chunk) => {
  buffer = Buffer.concat([buffer, chunk]);
  let end;
  while ((end = buffer.indexOf(0)) >= 0) {
    const msg = JSON.parse(buffer.subarray(0, end).toString("utf8"));
    buffer = buffer.subarray(end + 1);
    if (msg.id !== undefined && waiting.has(msg.id)) {
      const { resolve, reject } = waiting.get(msg.id);
      waiting.delete(msg.id);
      if (msg.error) reject(new Error(JSON.stringify(msg.error)));
      else resolve(msg.result);
    }
  }
});

function send(method, params = {}, sessionId) {
  const id = ++nextId;
  const msg = { id, method, params };
  if (sessionId) msg.sessionId = sessionId;
  toChrome.write(JSON.stringify(msg) + "\0");
  return new Promise((resolve, reject) => waiting.set(id, { resolve, reject }));
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// Closes the browser, then removes its profile: asked to close, it stops its helper
// processes and stops writing to the profile; one killed at once leaves helpers that
// write to it after it has been removed (and a directory left in the temporary folder
// on every run). A browser that does not close within two seconds is killed.
function finish(code, message) {
  if (message) process.stderr.write(message + "\n");
  const done = () => {
    try {
      fs.rmSync(profile, { recursive: true, force: true, maxRetries: 10, retryDelay: 50 });
    } catch (e) {}
    process.exit(code);
  };
  if (chrome.exitCode !== null || chrome.signalCode !== null) return done();
  chrome.once("exit", () => setTimeout(done, 100));
  try {
    toChrome.write(JSON.stringify({ id: ++nextId, method: "Browser.close" }) + "\0");
  } catch (e) {}
  setTimeout(() => {
    try {
      chrome.kill("SIGKILL");
    } catch (e) {}
  }, 2000);
  setTimeout(done, 4000);
}

const overall = timeoutMs * (args.includes("--examples") ? 20 : 1) + 10000;
setTimeout(() => finish(2, `timed out after ${overall} ms`), overall).unref();

async function evaluate(session, expression) {
  const r = await send("Runtime.evaluate", { expression, returnByValue: true, awaitPromise: true }, session);
  if (r.exceptionDetails) throw new Error(JSON.stringify(r.exceptionDetails));
  return r.result.value;
}

// The longest the page took to answer one poll: the page's main thread is blocked
// that long (a poll is evaluated on it).
let slowestPoll = 0;

// Waits until the page is done with the text it holds: not loading, not checking,
// not building the page.
async function settled(session, deadline) {
  for (;;) {
    const asked = Date.now();
    const kind = await evaluate(
      session,
      `(() => { const s = document.getElementById("status"); return s ? (s.dataset.kind || "") : ""; })()`,
    ).catch(() => "");
    slowestPoll = Math.max(slowestPoll, Date.now() - asked);
    if (["ok", "failed", "error", "empty"].includes(kind)) return kind;
    if (Date.now() > deadline) throw new Error(`the page did not finish checking (status: ${kind || "none"})`);
    await sleep(100);
  }
}

const SNAPSHOT = `(() => {
  const q = (s) => Array.from(document.querySelectorAll(s));
  const elements = {};
  for (const e of q("#preview *")) elements[e.localName] = (elements[e.localName] || 0) + 1;
  return {
    status: document.getElementById("status").dataset.kind,
    statusText: document.getElementById("status").textContent,
    summary: document.getElementById("summary").textContent,
    marks: q("[data-status]").map((e) => [e.dataset.status, Number(e.dataset.line), e.dataset.detail || ""]),
    diagnostics: q(".diag").map((e) => [e.dataset.severity, e.dataset.line ? Number(e.dataset.line) : null, e.textContent]),
    preview: document.getElementById("preview").textContent,
    elements,
    scriptRan: !!window.__rigorInjected,
    hash: location.hash,
    exampleNames: q("[data-example]").map((e) => e.dataset.example),
    katexErrors: q("#preview .katex-error").map((e) => e.title || e.textContent),
    cuts: q("[data-cut]").map((e) => e.dataset.cut),
    editorLength: document.getElementById("source").value.length,
    longestTask: window.__rigorLongestTask || 0,
  };
})()`;

(async () => {
  const { targetId } = await send("Target.createTarget", { url: "about:blank" });
  const { sessionId } = await send("Target.attachToTarget", { targetId, flatten: true });
  await send("Page.enable", {}, sessionId);
  // The longest task on the page's main thread, from before its scripts run.
  await send(
    "Page.addScriptToEvaluateOnNewDocument",
    {
      source: `window.__rigorLongestTask = 0;
        try {
          new PerformanceObserver((list) => {
            for (const e of list.getEntries())
              window.__rigorLongestTask = Math.max(window.__rigorLongestTask, e.duration);
          }).observe({ entryTypes: ["longtask"] });
        } catch (e) {}`,
    },
    sessionId,
  );
  await send("Page.navigate", { url }, sessionId);
  const deadline = Date.now() + timeoutMs;
  await sleep(200);
  await settled(sessionId, deadline);
  const typed = opt("--type");
  if (typed !== null) {
    // As a user would: replace the text and fire an input event (the page debounces).
    await evaluate(
      sessionId,
      `(() => { const s = document.getElementById("source"); s.value = ${JSON.stringify(typed)};
                s.dispatchEvent(new Event("input")); })()`,
    );
    await sleep(500);
    await settled(sessionId, deadline);
  }
  const snapshot = await evaluate(sessionId, SNAPSHOT);
  if (args.includes("--examples")) {
    snapshot.examples = [];
    for (const name of snapshot.exampleNames) {
      await evaluate(
        sessionId,
        `(() => { document.getElementById("status").dataset.kind = "busy";
                  document.querySelector('[data-example=${JSON.stringify(name)}]').click(); })()`,
      );
      const kind = await settled(sessionId, Date.now() + timeoutMs);
      const summary = await evaluate(sessionId, `document.getElementById("summary").textContent`);
      const errors = await evaluate(
        sessionId,
        `Array.from(document.querySelectorAll("#preview .katex-error")).map((e) => e.title || e.textContent)`,
      );
      snapshot.examples.push([name, kind, summary, errors]);
    }
  }
  const shot = opt("--screenshot");
  if (shot) {
    const { data } = await send("Page.captureScreenshot", { format: "png" }, sessionId);
    fs.writeFileSync(shot, Buffer.from(data, "base64"));
  }
  snapshot.slowestPoll = slowestPoll;
  // Exit once the output is written: a pipe takes a large snapshot in pieces.
  process.stdout.write(JSON.stringify(snapshot) + "\n", () => finish(0));
})().catch((e) => finish(1, String(e && e.stack ? e.stack : e)));
