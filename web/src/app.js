// The playground page: an editor, each link's verdict beside its line, the diagnostics,
// and the worked solution. Everything that comes from a derivation (prose, titles,
// labels, names, diagnostics) reaches the page as text nodes: elements are built here,
// never from markup in the file, and innerHTML is not used at all.
"use strict";

const DEBOUNCE_MS = 300;
// A check that has not answered by then is stopped (the checker's own budget is 3 s
// per claim; this catches a file of many slow claims, or a hang). The same deadline
// covers showing the answer: the page is built in slices between which it stays
// responsive, and what is not shown by then is left out, and the page says so.
const WATCHDOG_MS = 20000;
// One slice of building the page, in ms: the page answers input between slices.
const SLICE_MS = 25;
// The worked solution shows at most this many blocks (each may be typeset by KaTeX);
// the verdicts beside the lines and the diagnostics cover the whole file.
const MAX_PREVIEW_BLOCKS = 400;
// Diagnostics listed at most (the gutter marks every line).
const MAX_DIAGNOSTICS = 1000;

const $ = (id) => document.getElementById(id);
const source = $("source");
const gutter = $("gutter");
const status = $("status");

let examples = {};
let fileName = "playground.deriv";
let worker = null;
let nextId = 0;
let pending = null; // {id, timer, text, deadline}
let debounce = null;
let showing = null; // the answer being shown: {cancelled}

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

// The text of a `#src=` link: {text}, {unreadable} when the link holds no derivation
// that can be read, or null without a `#src=` link.
function sourceFromHash() {
  if (!location.hash.startsWith("#src=")) return null;
  const m = /^#src=([A-Za-z0-9_-]*)$/.exec(location.hash);
  try {
    if (!m) throw new Error("not base64url");
    return { text: decodeSource(m[1]) };
  } catch (e) {
    return { unreadable: true };
  }
}

// A link that cannot be read checks nothing and claims nothing: the editor, the
// verdicts, the diagnostics and the preview are emptied, and the status says why.
function unreadableLink() {
  cancelShowing();
  if (pending) clearTimeout(pending.timer);
  pending = null;
  clearTimeout(debounce);
  source.value = "";
  renderGutter(1, new Map());
  clear($("diagnostics"));
  clear($("preview"));
  const summary = $("summary");
  delete summary.dataset.ok;
  summary.textContent = "";
  setStatus("error", "this link cannot be read: it is not a derivation encoded as base64url of UTF-8 text, so nothing was checked");
}

function openLink(fallback) {
  const link = sourceFromHash();
  if (link === null) return fallback();
  if (link.unreadable) return unreadableLink();
  load("playground.deriv", link.text);
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
    const { text, deadline } = pending;
    pending = null;
    if (msg.crash) {
      setStatus("error", "the checker stopped: " + msg.crash);
      return;
    }
    show(msg.answer, text, msg.ms, deadline);
  };
  worker.onerror = (e) => setStatus("error", "the checker could not run: " + e.message);
}

function check() {
  const text = source.value;
  if (pending) clearTimeout(pending.timer);
  cancelShowing();
  const id = ++nextId;
  const timer = setTimeout(() => {
    // Stop it: a new worker serves the next edit, and the page stays responsive.
    worker.terminate();
    pending = null;
    startWorker();
    setStatus("error", `stopped: checking took longer than ${WATCHDOG_MS / 1000} s`);
  }, WATCHDOG_MS);
  pending = { id, timer, text, deadline: performance.now() + WATCHDOG_MS };
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
// only the marks change. `marks` null: the text changed and is not checked yet. The
// work is a list of steps, each a few hundred rows or marks, so that a long file is
// built in slices (see inSlices).
function gutterSteps(lines, marks) {
  const BATCH = 500;
  const steps = [
    () => {
      while (gutter.children.length > lines) gutter.lastChild.remove();
      gutter.dataset.stale = String(marks === null);
    },
  ];
  for (let k = Math.max(0, lines - gutter.children.length); k > 0; k -= BATCH) {
    steps.push(() => {
      const frag = document.createDocumentFragment();
      const to = Math.min(lines, gutter.children.length + BATCH);
      for (let n = gutter.children.length + 1; n <= to; n++) {
        frag.append(el("div", { class: "ln" }, el("span", { class: "num" }, String(n)), el("span", { class: "marks" })));
      }
      gutter.append(frag);
    });
  }
  if (marks === null) return steps; // typing: the last verdicts stay, dimmed, until the next
  steps.push(() => {
    for (const row of gutter.querySelectorAll(".marks:not(:empty)")) clear(row);
  });
  const entries = Array.from(marks);
  for (let i = 0; i < entries.length; i += BATCH) {
    steps.push(() => {
      for (const [n, list] of entries.slice(i, i + BATCH)) {
        const row = gutter.children[n - 1];
        if (row) for (const mark of list) row.lastChild.append(mark);
      }
    });
  }
  steps.push(() => {
    gutter.scrollTop = source.scrollTop;
  });
  return steps;
}

// Brings the gutter to `lines` rows in slices; a later call takes over from an
// earlier one that has not finished.
let gutterJob = null;
function renderGutter(lines, marks) {
  if (gutterJob) gutterJob.cancelled = true;
  gutterJob = { cancelled: false };
  return inSlices(gutterJob, gutterSteps(lines, marks), Infinity);
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

function cancelShowing() {
  if (showing) showing.cancelled = true;
  showing = null;
}

// Runs `steps` (functions) in slices of SLICE_MS, yielding to the page between
// slices; stops at `deadline` or when `job` is cancelled. Resolves to whether every
// step ran.
function inSlices(job, steps, deadline) {
  return new Promise((resolve) => {
    let i = 0;
    const slice = () => {
      if (job.cancelled) return resolve(false);
      const end = performance.now() + SLICE_MS;
      while (i < steps.length && performance.now() < end) steps[i++]();
      if (i >= steps.length) return resolve(true);
      if (performance.now() > deadline) return resolve(false);
      setTimeout(slice, 0);
    };
    slice();
  });
}

// The number of links of a report.
function linkCount(report) {
  let n = 0;
  for (const claim of report.claims) n += claim.links.length;
  return n;
}

// The status line for a checked file: "nothing to check" for a file with no step,
// "all steps verified" only when there are steps and every one verified.
function verdictStatus(answer) {
  const n = linkCount(answer.report);
  if (!answer.ok) return ["failed", "not all steps verified"];
  if (n === 0) return ["empty", "nothing to check: no claim, so no step was verified"];
  return ["ok", n === 1 ? "the one step verified" : `all ${n} steps verified`];
}

async function show(answer, text, ms, deadline) {
  cancelShowing();
  const job = { cancelled: false };
  showing = job;
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
  const linkLines = new Set();
  for (const claim of report.claims) {
    for (const link of claim.links) {
      const st = pageStatus(link.status);
      const line = link.line ?? claim.line;
      linkLines.add(link.line);
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
    if (!linkLines.has(d.line)) add(d.line, verdictMark("error", d.code, d.line, d.message));
  }
  if (gutterJob) gutterJob.cancelled = true;
  const [kind, words] = verdictStatus(answer);
  const summary = $("summary");
  summary.dataset.ok = kind === "empty" ? "empty" : String(answer.ok);
  summary.textContent = answer.summary;
  const timing = ` · ${Math.round(ms)} ms`;
  // Until the page is built the status says so; the verdict comes with the page.
  setStatus("busy", words + timing + " · showing…");
  const steps = [
    ...gutterSteps(lineCount(text), marks),
    ...diagnosticSteps(report, answer.rendered),
    ...solutionSteps(answer.solution),
  ];
  const done = await inSlices(job, steps, deadline);
  if (job.cancelled) return;
  showing = null;
  if (!done) {
    $("preview").append(
      el("p", { class: "cut", "data-cut": "deadline" },
        `The rest of the worked solution is not shown: showing it took longer than ${WATCHDOG_MS / 1000} s. The verdicts beside the lines cover the whole derivation.`),
    );
  }
  setStatus(kind, words + timing + (done ? "" : " · preview stopped"));
}

// The diagnostics list, built in steps (at most MAX_DIAGNOSTICS, then a line saying
// how many more there are).
function diagnosticSteps(report, rendered) {
  const box = $("diagnostics");
  const steps = [() => clear(box)];
  const shown = report.diagnostics.slice(0, MAX_DIAGNOSTICS);
  shown.forEach((d, i) => steps.push(() => box.append(diagnosticItem(d, rendered[i]))));
  const more = report.diagnostics.length - shown.length;
  if (more > 0) {
    steps.push(() => box.append(el("p", { class: "cut", "data-cut": "diagnostics" },
      `${more} more diagnostics are not listed; the marks beside the lines show every step.`)));
  }
  return steps;
}

function diagnosticItem(d, rendered) {
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
    el("pre", {}, rendered || d.message),
  );
  if (d.line != null) {
    const go = () => goToLine(d.line, d.column);
    item.addEventListener("click", go);
    item.addEventListener("keydown", (e) => {
      if (e.key === "Enter") go();
    });
  }
  return item;
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

// The worked solution, built in steps: one per block, at most MAX_PREVIEW_BLOCKS, then
// a line saying how many are left out.
function solutionSteps(solution) {
  const box = $("preview");
  const steps = [
    () => {
      clear(box);
      box.append(el("h2", { class: "title" }, inline(solution.title)));
    },
  ];
  // Each block is a step, and so is each item of a list of problems.
  let shown = 0;
  for (const b of solution.blocks) {
    if (shown >= MAX_PREVIEW_BLOCKS) break;
    if (b.kind === "problems") {
      for (const p of b.items) {
        if (shown++ >= MAX_PREVIEW_BLOCKS) break;
        steps.push(() => box.append(problemItem(p)));
      }
    } else {
      shown++;
      steps.push(() => renderBlock(box, b));
    }
  }
  const total = solution.blocks.reduce((n, b) => n + (b.kind === "problems" ? b.items.length : 1), 0);
  if (total > shown) {
    steps.push(() => box.append(el("p", { class: "cut", "data-cut": "blocks" },
      `The worked solution is cut here: ${total - shown} of its ${total} parts are not shown. The verdicts beside the lines cover the whole derivation.`)));
  }
  return steps;
}

function problemItem(p) {
  const head = el("strong", {}, p.kind);
  const where = p.line != null ? ` (line ${p.line})` : "";
  const q = el("blockquote", { class: "problem", "data-line": p.line }, head, where + ": " + p.message);
  // Each note is typeset by the worked solution's own pieces: text and math parts.
  for (const n of p.notes) q.append(el("div", { class: "note" }, Array.isArray(n) ? inline(n) : n));
  return q;
}

function renderBlock(box, b) {
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
      for (const p of b.items) box.append(problemItem(p));
      break;
    case "listing":
      box.append(el("pre", { class: "listing" }, b.lines.join("")));
      break;
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
  const link = sourceFromHash();
  if (link === null) return;
  if (link.unreadable) unreadableLink();
  else if (link.text !== source.value) load(fileName, link.text);
});

startWorker();
loadExamples().then(() =>
  openLink(() => {
    if (examples["rod.deriv"]) load("rod.deriv", examples["rod.deriv"]);
    else load("playground.deriv", "# A first derivation\nsymbols m L > 0\nclaim m L^2/12 + m (L/2)^2 = m L^2/3\n");
  }),
);
