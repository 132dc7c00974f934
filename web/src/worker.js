// The checker, off the page's thread: typing never waits for it. It answers each
// request {id, name, source, files} with {id, answer} (rigor::render::web::respond's
// JSON) or {id, crash} when the checker trapped; after a trap the instance is renewed.
"use strict";

let exports = null;

async function load() {
  const bytes = await (await fetch("rigor.wasm")).arrayBuffer();
  const { instance } = await WebAssembly.instantiate(bytes, {
    env: { rigor_now_ms: () => performance.now() },
  });
  exports = instance.exports;
}

let ready = load();

function check(request) {
  const input = new TextEncoder().encode(JSON.stringify(request));
  const ptr = exports.rigor_alloc(input.length);
  new Uint8Array(exports.memory.buffer, ptr, input.length).set(input);
  const len = exports.rigor_check(ptr, input.length);
  const at = exports.rigor_answer_ptr();
  // Copy before decoding: the memory may grow on the next call.
  const out = new Uint8Array(exports.memory.buffer, at, len).slice();
  return JSON.parse(new TextDecoder().decode(out));
}

self.onmessage = async (event) => {
  const { id, name, source, files } = event.data;
  try {
    await ready;
  } catch (e) {
    self.postMessage({ id, crash: "the checker could not be loaded: " + e });
    return;
  }
  const started = performance.now();
  try {
    const answer = check({ name, source, files, timeout_ms: 3000 });
    self.postMessage({ id, answer, ms: performance.now() - started });
  } catch (e) {
    self.postMessage({ id, crash: String(e) });
    ready = load();
  }
};
