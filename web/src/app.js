// The playground page: an editor, each link's verdict beside its line, the diagnostics,
// and the worked solution. Everything that comes from a derivation (prose, titles,
// labels, names, diagnostics) reaches the page as text nodes: elements are built here,
// never from markup in the file, and innerHTML is not used at all.
"use strict";

const DEBOUNCE_MS = 300;
// A check that has not answered by then is stopped (the checker's own budget is 3 s
// per claim; this catches a file of many slow claims, or a hang).
const WATCHDOG_MS = 20000;

const $ = (id) => document.getElementById(id);
const source = $("source");
const gutter = $("gutter");
const status = $("status");

let examples = {};
let fileName = "playground.deriv";
let worker = null;
let nextId = 0;
let pending = null; // {id, timer}
let debounce = null;

// ---- small DOM helpers (text only) ----

function el(tag, attrs, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (v !== null && v !== undefined) node.setAttribute(k, String(v));
  }
  for (const c of children) {
    if (c === null || c === undefined) continue;
    node.append(typeof c === "string" ? document.createTextNode(c) : c);
  }
  return node;
}

function clear(node) {
  while (node.firstChild) node.removeChild(node.firstChild);
}

// ---- the URL fragment: #src=<base64url of the UTF-8 text> ----

function encodeSource(text) {
  const bytes = new TextEncoder().encode(text);
  let bin = "";
  for (let i = 0; i < bytes.length; i += 0x8000) {
    bin += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  }
  return btoa(bin).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

function decodeSource(b64) {
  const std = b64.replace(/-/g, "+").replace(/_/g, "/");
  const bin = atob(std + "===".slice((std.length + 3) % 4));
  const bytes = Uint8Array.from(bin, (c) => c.charCodeAt(0));
  return new TextDecoder("utf-8", { fatal: true }).decode(bytes);
}

function sourceFromHash() {
  const m = /^#src=([A-Za-z0-9_-]*)$/.exec(location.hash);
  if (!m) return null;
  try {
    return decodeSource(m[1]);
  } catch (e) {
    setStatus("error", "the link's derivation could not be read (it is not base64url of UTF-8 text)");
    return "";
  }
}

function keepInUrl() {
  const hash = "#src=" + encodeSource(source.value);
  if (location.hash !== hash) history.replaceState(null, "", hash);
}

// ---- the worker ----

function startWorker() {
  worker = new Worker("worker.js");
  worker.onmessage = (event) => {
    const msg = event.data;
    if (!pending || msg.id !== pending.id) return; // an answer to an older text
    clearTimeout(pending.timer);
    const text = pending.text;
    pending = null;
    if (msg.crash) {
      setStatus("error", "the checker stopped: " + msg.crash);
      return;
    }
    show(msg.answer, text, msg.ms);
  };
  worker.onerror = (e) => setStatus("error", "the checker could not run: " + e.message);
}

function check() {
  const text = source.value;
  if (pending) clearTimeout(pending.timer);
  const id = ++nextId;
  const timer = setTimeout(() => {
    // Stop it: a new worker serves the next edit, and the page stays responsive.
    worker.terminate();
    pending = null;
    startWorker();
    setStatus("error", `stopped: checking took longer than ${WATCHDOG_MS / 1000} s`);
  }, WATCHDOG_MS);
  pending = { id, timer, text };
  setStatus("busy", "checking…");
  worker.postMessage({ id, name: fileName, source: text, files: examples });
}

function scheduleCheck() {
  clearTimeout(debounce);
  debounce = setTimeout(() => {
    keepInUrl();
    check();
  }, DEBOUNCE_MS);
  renderGutter(lineCount(source.value), null);
}

// ---- showing an answer ----

function setStatus(kind, text) {
  status.dataset.kind = kind;
  status.textContent = text;
}

function lineCount(text) {
  return text.split("\n").length;
}

// The four statuses the page shows; a link not checked because what it cites failed
// is shown as undecided, with the detail kept.
function pageStatus(s) {
  return s === "not_checked" ? "undecided" : s;
}

const SYMBOL = { verified: "✓", failed: "✗", undecided: "?", error: "!" };
const WORDS = {
  verified: "verified",
  failed: "does not hold",
  undecided: "not verified",
  error: "could not be checked",
};

// One row per line, kept between checks (a long file is not rebuilt per keystroke);
// only the marks change. `marks` null: the text changed and is not checked yet.
function renderGutter(lines, marks) {
  while (gutter.children.length > lines) gutter.lastChild.remove();
  for (let n = gutter.children.length + 1; n <= lines; n++) {
    gutter.append(el("div", { class: "ln" }, el("span", { class: "num" }, String(n)), el("span", { class: "marks" })));
  }
  gutter.dataset.stale = String(marks === null);
  if (marks === null) return; // typing: the last verdicts stay, dimmed, until the next
  for (const row of gutter.querySelectorAll(".marks:not(:empty)")) clear(row);
  for (const [n, list] of marks) {
    const row = gutter.children[n - 1];
    if (row) for (const mark of list) row.lastChild.append(mark);
  }
  gutter.scrollTop = source.scrollTop;
}

function verdictMark(status, detail, line, title) {
  return el(
    "span",
    {
      class: "mark " + status,
      "data-status": status,
      "data-line": line,
      "data-detail": detail,
      title,
    },
    SYMBOL[status],
  );
}

function show(answer, text, ms) {
  if (answer.error) {
    setStatus("error", answer.error);
    return;
  }
  const report = answer.report;
  const marks = new Map();
  const add = (line, node) => {
    if (!marks.has(line)) marks.set(line, []);
    marks.get(line).push(node);
  };
  for (const claim of report.claims) {
    for (const link of claim.links) {
      const st = pageStatus(link.status);
      const line = link.line ?? claim.line;
      let title = WORDS[st];
      if (link.status === "not_checked") title = "not checked: it cites a step that did not hold";
      if (link.justification && link.justification.kind === "facts") {
        title += " using " + link.justification.facts.map((f) => "[" + f + "]").join(", ");
      }
      add(line, verdictMark(st, link.status, line, title));
    }
  }
  // Input errors outside any link (a syntax error, an undeclared name in a given).
  for (const d of report.diagnostics) {
    if (d.severity !== "error" || d.line == null) continue;
    const inLink = report.claims.some((c) => c.links.some((l) => l.line === d.line));
    if (!inLink) add(d.line, verdictMark("error", d.code, d.line, d.message));
  }
  renderGutter(lineCount(text), marks);
  renderDiagnostics(report, answer.rendered);
  const summary = $("summary");
  summary.dataset.ok = String(answer.ok);
  summary.textContent = answer.summary;
  renderSolution(answer.solution);
  setStatus(answer.ok ? "ok" : "failed", (answer.ok ? "all steps verified" : "not all steps verified") + ` · ${Math.round(ms)} ms`);
}

function renderDiagnostics(report, rendered) {
  const box = $("diagnostics");
  clear(box);
  report.diagnostics.forEach((d, i) => {
    const item = el(
      "div",
      {
        class: "diag " + d.severity,
        "data-severity": d.severity,
        "data-code": d.code,
        "data-line": d.line,
        tabindex: "0",
        title: d.line != null ? "go to line " + d.line : null,
      },
      el("pre", {}, rendered[i] || d.message),
    );
    if (d.line != null) {
      const go = () => goToLine(d.line, d.column);
      item.addEventListener("click", go);
      item.addEventListener("keydown", (e) => {
        if (e.key === "Enter") go();
      });
    }
    box.append(item);
  });
}

function goToLine(line, column) {
  const lines = source.value.split("\n");
  let at = 0;
  for (let i = 0; i < line - 1 && i < lines.length; i++) at += lines[i].length + 1;
  // Columns are characters; the textarea counts UTF-16 units.
  const text = lines[line - 1] || "";
  const col = Array.from(text).slice(0, Math.max(0, (column || 1) - 1)).join("").length;
  source.focus();
  source.setSelectionRange(at + col, at + text.length);
  const lh = parseFloat(getComputedStyle(source).lineHeight) || 18;
  source.scrollTop = Math.max(0, (line - 3) * lh);
}

// ---- the worked solution ----

function math(latex, display) {
  const span = el("span", { class: display ? "math display" : "math" });
  if (window.katex) {
    // KaTeX builds its own elements from the LaTeX that rigor wrote (text inside it is
    // escaped by rigor; `trust` stays off, so no links or classes from the input).
    katex.render(latex, span, {
      displayMode: display,
      throwOnError: false,
      trust: false,
      strict: "ignore",
      output: "htmlAndMathml",
    });
  } else {
    span.textContent = latex;
  }
  return span;
}

function inline(parts) {
  const frag = document.createDocumentFragment();
  for (const p of parts) {
    if ("text" in p) frag.append(document.createTextNode(p.text));
    else if ("strong" in p) frag.append(el("strong", {}, p.strong));
    else if ("code" in p) frag.append(el("code", {}, p.code));
    else if ("math" in p) frag.append(math(p.math, false));
  }
  return frag;
}

function renderSolution(solution) {
  const box = $("preview");
  clear(box);
  box.append(el("h2", { class: "title" }, inline(solution.title)));
  for (const b of solution.blocks) {
    switch (b.kind) {
      case "heading":
        box.append(el("h" + Math.min(6, Math.max(3, b.level + 1)), {}, inline(b.parts)));
        break;
      case "paragraph":
        box.append(el("p", {}, inline(b.parts)));
        break;
      case "display":
        if (b.prefix) box.append(el("p", { class: "prefix" }, b.prefix));
        box.append(el("div", { class: "eq" }, math(b.latex, true)));
        break;
      case "claim":
        box.append(el("div", { class: "eq claim" }, math(b.latex, true)));
        break;
      case "problems":
        for (const p of b.items) {
          const head = el("strong", {}, p.kind);
          const where = p.line != null ? ` (line ${p.line})` : "";
          const q = el("blockquote", { class: "problem", "data-line": p.line }, head, where + ": " + p.message);
          for (const n of p.notes) q.append(el("div", { class: "note" }, n));
          box.append(q);
        }
        break;
      case "listing":
        box.append(el("pre", { class: "listing" }, b.lines.join("")));
        break;
    }
  }
}

// ---- examples ----

function load(name, text) {
  fileName = name;
  source.value = text;
  source.scrollTop = 0;
  keepInUrl();
  renderGutter(lineCount(text), new Map());
  check();
}

async function loadExamples() {
  try {
    examples = await (await fetch("examples.json")).json();
  } catch (e) {
    examples = {};
  }
  const nav = $("examples");
  for (const name of Object.keys(examples)) {
    const b = el("button", { type: "button", class: "example", "data-example": name }, name.replace(/\.deriv$/, ""));
    b.addEventListener("click", () => load(name, examples[name]));
    nav.append(b);
  }
}

// ---- start ----

source.addEventListener("input", scheduleCheck);
source.addEventListener("scroll", () => {
  gutter.scrollTop = source.scrollTop;
});
source.addEventListener("keydown", (e) => {
  if (e.key === "Tab" && !e.shiftKey) {
    e.preventDefault();
    source.setRangeText("  ", source.selectionStart, source.selectionEnd, "end");
    scheduleCheck();
  }
});
$("share").addEventListener("click", async () => {
  keepInUrl();
  try {
    await navigator.clipboard.writeText(location.href);
    setStatus("ok", "link copied");
  } catch (e) {
    setStatus("ok", "the link is in the address bar");
  }
});
window.addEventListener("hashchange", () => {
  const text = sourceFromHash();
  if (text !== null && text !== source.value) load(fileName, text);
});

startWorker();
loadExamples().then(() => {
  const text = sourceFromHash();
  if (text !== null) load("playground.deriv", text);
  else if (examples["rod.deriv"]) load("rod.deriv", examples["rod.deriv"]);
  else load("playground.deriv", "# A first derivation\nsymbols m L > 0\nclaim m L^2/12 + m (L/2)^2 = m L^2/3\n");
});
