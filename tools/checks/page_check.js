/*
 * page_check.js -- the book's scenes rendered in its own page, in headless
 * Chromium driven through the DevTools protocol on a pipe (no npm module,
 * no network port): tools/checks/page_check.sh runs it.
 *
 *   node tools/checks/page_check.js BROWSER BOOK.html CASES.json
 *
 * CASES.json: { "renders": [ { "chapter", "scene", "size", "reference" }
 * ...], "mistake": { "chapter", "text", "expected" }, "pixelMistake": {
 * "chapter", "text", "pixel", "expected" }, "progress": { "chapter", "size",
 * "pixel", "text" }, "long": { "chapter", "size", "pixel" } }: every render
 * is made in the page (the playground of
 * that chapter and scene, at --size size) and compared with reference, a
 * PNG that bin/chNN drew (base64): each channel within 1 code, and how
 * many pixels differ at all is printed. The mistake's text, in the
 * chapter's empty scene, must give the program's own error line expected
 * (as bin/chNN wrote it for the same file name) and select that line and
 * column in the editor; the pixel mistake, bin/chNN's line for the same
 * --pixel, shown as the option's, selected in the --pixel box and not in
 * the editor. The render of "progress" must show its progress line in the
 * status while it runs, and leave none in the statistics under it
 * (--stats). The long render must be cancelled within a second
 * of Cancel, and the playground must render again afterwards. The network
 * is off for the whole page (offline, and no request but file:, data: and
 * blob: may be made). "control" is a render whose reference is another
 * scene's: it must differ, so that the comparison is seen to be able to
 * fail. "mistake" and "pixelMistake" go together, as do "progress" and
 * "long": either pair may be left out (page_check.sh --scenes does).
 * With "layout": { "script", "width", "height" }, the page is loaded at
 * width x height with no scroll bars, and the script (book_check.js, the
 * layout check of make book-check) runs in it before any render: each
 * problem it writes is a failure, and its summary line is printed (one
 * load of the book serves both checks).
 * Prints one line a check; exits 1 on any failure.
 *
 * With "speed": { "bin", "clangBin", "chapters", "size", "rounds", "csv" } in
 * CASES.json it measures instead: each chapter's own scene (no scene file)
 * at --size size, drawn by bin/chNN on one thread and by the program in
 * the page, rounds times, interleaved; the render's time is what --stats
 * says of it in both. It writes csv (the benchmarks' columns: the median
 * and quartiles of each, and the ratio of the medians, page over native).
 */
"use strict";
const { spawn, spawnSync } = require("child_process");
const fs = require("fs");
const os = require("os");
const path = require("path");

const [browser, book, casesFile] = process.argv.slice(2);
const cases = JSON.parse(fs.readFileSync(casesFile, "utf8"));
const profile = fs.mkdtempSync(path.join(os.tmpdir(), "page-check-"));
const flags = ["--headless", "--disable-gpu", "--disable-dev-shm-usage",
               "--remote-debugging-pipe", "--user-data-dir=" + profile,
               "--host-resolver-rules=MAP * ~NOTFOUND", "about:blank"];
if (process.getuid && process.getuid() === 0) flags.unshift("--no-sandbox");
const chrome = spawn(browser, flags, { stdio: ["ignore", "ignore", "pipe", "pipe", "pipe"] });
let browserLog = "";
chrome.stderr.on("data", (d) => { browserLog = (browserLog + d).slice(-2000); });

// The protocol: JSON messages ended by a NUL byte, ours on fd 3, its on fd 4.
let nextId = 1, pending = new Map(), listeners = [], buffered = "";
chrome.stdio[4].on("data", (data) => {
  buffered += data.toString("utf8");
  let end;
  while ((end = buffered.indexOf("\0")) >= 0) {
    const message = JSON.parse(buffered.slice(0, end));
    buffered = buffered.slice(end + 1);
    if (message.id && pending.has(message.id)) {
      const { resolve, reject } = pending.get(message.id);
      pending.delete(message.id);
      if (message.error) reject(new Error(JSON.stringify(message.error)));
      else resolve(message.result);
    } else listeners.forEach((listen) => listen(message));
  }
});
function send(method, params, sessionId) {
  const id = nextId++;
  chrome.stdio[3].write(JSON.stringify({ id, method, params: params || {}, sessionId }) + "\0");
  return new Promise((resolve, reject) => pending.set(id, { resolve, reject }));
}

let failures = 0;
function report(ok, line) {
  console.log("page-check: " + (ok ? "" : "error: ") + line);
  if (!ok) failures++;
}

// Runs fn (a function's source) in the page with arg, and returns what
// its promise gives.
async function inPage(session, fn, arg) {
  const result = await send("Runtime.evaluate", {
    expression: "(" + fn + ")(" + JSON.stringify(arg) + ")",
    awaitPromise: true, returnByValue: true }, session);
  if (result.exceptionDetails)
    throw new Error("in the page: " + JSON.stringify(result.exceptionDetails).slice(0, 500));
  return result.result.value;
}

// Everything below runs in the page.
const PAGE_HELPERS = `
  function playground(chapter, scene) {
    var all = document.querySelectorAll("div.playground");
    for (var i = 0; i < all.length; i++)
      if (+all[i].dataset.chapter === +chapter && (all[i].dataset.scene || "") === (scene || ""))
        return all[i];
    return null;
  }
  function settled(div, limit) {
    return new Promise(function (resolve) {
      var start = performance.now();
      (function poll() {
        if (div.dataset.state !== "rendering" || performance.now() - start > limit)
          resolve(div.dataset.state);
        else setTimeout(poll, 20);
      })();
    });
  }
  function pixelsOf(source, width, height) {
    var c = document.createElement("canvas");
    c.width = width; c.height = height;
    var g = c.getContext("2d");
    g.drawImage(source, 0, 0);
    return g.getImageData(0, 0, width, height).data;
  }
`;

function renderInPage(c) {
  /* eslint-disable no-undef */
  return (async function () {
    HELPERS;
    var div = playground(c.chapter, c.scene);
    if (!div || !div.querySelector("button.playground-render")) return { error: "no playground" };
    div.querySelector("details").open = true;
    div.querySelector("input").value = c.size;
    if (c.text !== undefined) div.querySelector("textarea").value = c.text;
    var pixel = div.querySelectorAll("input")[1];
    if (pixel) pixel.value = c.pixel || "";
    div.querySelector("button.playground-render").click();
    if (c.cancelAfter) {
      await new Promise(function (r) { setTimeout(r, c.cancelAfter); });
      var before = div.dataset.state;
      var t = performance.now();
      div.querySelector("button.playground-cancel").click();
      var state = div.dataset.state;
      await new Promise(function (r) { setTimeout(r, 1000); });
      return { before: before, state: state, after: div.dataset.state,
               ms: performance.now() - t };
    }
    var progress = "", seen = new MutationObserver(function () {
      var now = div.querySelector(".playground-status").textContent;
      if (/rays\/s/.test(now)) progress = now;
    });
    seen.observe(div.querySelector(".playground-status"), { childList: true, characterData: true, subtree: true });
    var state = await settled(div, 120000);
    seen.disconnect();
    var out = { state: state, status: div.querySelector(".playground-status").textContent,
                stderr: div.querySelector(".playground-stats").textContent, progress: progress };
    if (c.text !== undefined) {
      var editor = div.querySelector("textarea");
      out.selection = [editor.selectionStart, editor.selectionEnd];
      out.textLength = editor.value.length;
    }
    if (pixel) out.pixelSelection = [pixel.selectionStart, pixel.selectionEnd];
    if (state !== "done" || !c.reference) return out;
    var canvas = div.querySelector("canvas");
    var image = new Image();
    image.src = "data:image/png;base64," + c.reference;
    await image.decode();
    out.width = canvas.width; out.height = canvas.height;
    out.referenceWidth = image.naturalWidth; out.referenceHeight = image.naturalHeight;
    if (canvas.width !== image.naturalWidth || canvas.height !== image.naturalHeight) return out;
    var a = pixelsOf(canvas, canvas.width, canvas.height);
    var b = pixelsOf(image, canvas.width, canvas.height);
    var largest = 0, differ = 0;
    for (var i = 0; i < a.length; i += 4) {
      var d = Math.max(Math.abs(a[i] - b[i]), Math.abs(a[i + 1] - b[i + 1]),
                       Math.abs(a[i + 2] - b[i + 2]), Math.abs(a[i + 3] - b[i + 3]));
      if (d > 0) differ++;
      if (d > largest) largest = d;
    }
    out.largest = largest; out.differ = differ;
    return out;
  })();
}

// The offset in text of line:column (both from 1).
function offsetOf(text, line, column) {
  const lines = text.split("\n");
  let at = 0;
  for (let i = 0; i < line - 1; i++) at += lines[i].length + 1;
  return at + column - 1;
}

// "render 118.0 ms" of --stats, in ms.
function renderMs(stderr) {
  if (typeof stderr !== "string") throw new Error("no standard error: " + stderr);
  const m = /^time +scene [0-9.]+ ms, render ([0-9.]+) ms/m.exec(stderr);
  if (!m) throw new Error("no render time in: " + stderr.slice(-300));
  return +m[1];
}

// A chapter's own scene in the page, through a worker of the page's own.
function pageRender(job) {
  return new Promise(function (resolve) {
    var code = document.getElementById("rt-worker").textContent;
    var worker = new Worker(URL.createObjectURL(new Blob([code], { type: "text/javascript" })));
    worker.onmessage = function (event) {
      if ("progress" in event.data) return; /* a render past a second: not done yet */
      worker.terminate();
      resolve(event.data.stderr);
    };
    worker.postMessage({ program: document.getElementById("rt-program-" + job.chapter).textContent.trim(),
                         scene: "", sceneName: "scenes/none.scene", meshes: [],
                         args: ["-o", "-", "--stats", "--size", job.size] });
  });
}

function quartiles(list) {
  const s = list.slice().sort((a, b) => a - b);
  const at = (q) => s[Math.min(s.length - 1, Math.round(q * (s.length - 1)))];
  return [at(0.25), at(0.5), at(0.75)];
}

async function speed(sessionId, c) {
  const times = {};
  for (let round = 0; round < c.rounds; round++) {
    for (const n of c.chapters) {
      const threads = +n >= 12 ? ["--threads", "1"] : []; /* from chapter 12 */
      const args = ["-o", "/dev/null", "--stats", "--size", c.size].concat(threads);
      const native = spawnSync(c.bin + "/ch" + n, args, { encoding: "utf8" });
      const page = await inPage(sessionId, pageRender.toString(), { chapter: n, size: c.size });
      (times["native," + n] = times["native," + n] || []).push(renderMs(native.stderr));
      (times["page," + n] = times["page," + n] || []).push(renderMs(page));
      if (c.clangBin) { /* the page's compiler, for the machine */
        const clang = spawnSync(c.clangBin + "/ch" + n, args, { encoding: "utf8" });
        (times["clang," + n] = times["clang," + n] || []).push(renderMs(clang.stderr));
      }
    }
  }
  const rows = ["method,param,ns_per_op,error,error_kind,ns_q1,ns_q3,wall_ns"];
  for (const n of c.chapters) {
    const median = {};
    for (const method of c.clangBin ? ["native", "clang", "page"] : ["native", "page"]) {
      const [q1, q2, q3] = quartiles(times[method + "," + n]);
      median[method] = q2;
      rows.push([method, "ch" + n, (q2 * 1e6).toFixed(0), q2.toFixed(2), "render_ms",
                 (q1 * 1e6).toFixed(0), (q3 * 1e6).toFixed(0), (q2 * 1e6).toFixed(0)].join(","));
    }
    rows.push(["ratio", "ch" + n, 0, (median.page / median.native).toFixed(3), "page_over_native"].join(","));
    if (c.clangBin)
      rows.push(["ratio", "ch" + n, 0, (median.page / median.clang).toFixed(3), "page_over_clang"].join(","));
    report(true, "chapter " + n + ": " + median.native + " ms native, " + median.page + " ms in the page");
  }
  fs.writeFileSync(c.csv, c.machine + "\n# size: " + c.size + "\n" + rows.join("\n") + "\n");
}

// A mistake in the scene, and one in --pixel: each the program's own line
// as bin/chNN wrote it, selected where it is.
async function mistakes(run) {
  const m = cases.mistake;
  const r = await run({ chapter: m.chapter, scene: "", size: "", text: m.text });
  const expected = m.expected.trim();
  const where = /:(\d+):(\d+): error: /.exec(expected);
  const want = where ? offsetOf(m.text, +where[1], +where[2]) : -1;
  report(r.state === "error" && r.stderr.trim() === expected && r.selection[0] === want,
         "a mistake (the playground's state: " + r.state + "): \"" + r.status + "\", the program's line " +
         (r.stderr.trim() === expected ? "as bin/ch" + m.chapter + " wrote it" : JSON.stringify(r.stderr)) +
         ", selected from " + r.selection[0] + " (its column: " + want + ")");

  // A mistake in --pixel is the option's: said so, and selected in its
  // box, not in the scene's text.
  const px = cases.pixelMistake;
  const pr = await run({ chapter: px.chapter, scene: "", size: "", text: px.text, pixel: px.pixel });
  const pwhere = /^--pixel:1:(\d+): error: (.*)$/.exec(px.expected.trim());
  const pcol = pwhere ? +pwhere[1] : -1;
  report(pr.state === "error" && pr.stderr.trim() === px.expected.trim() &&
         pr.status === "--pixel, column " + pcol + ": " + (pwhere ? pwhere[2] : "") &&
         pr.selection[0] === pr.selection[1] && pr.pixelSelection[0] === pcol - 1,
         "a --pixel mistake: \"" + pr.status + "\", the scene's text selected from " +
         pr.selection[0] + " to " + pr.selection[1] + ", the --pixel box from " +
         pr.pixelSelection[0] + " (its column: " + pcol + ")");
}

// A render of some seconds, its progress shown, and a long one cancelled.
async function longRenders(run) {
  // A render of a few seconds, with --stats: its progress in the status
  // line while it runs, and none of it left in the statistics.
  const g = cases.progress;
  const gr = await run({ chapter: g.chapter, scene: "", size: g.size, pixel: g.pixel, text: g.text });
  const stale = gr.stderr.split("\n").filter((line) => /\] +[0-9]+%|\r|, [0-9]+ s$/.test(line));
  report(gr.state === "done" && gr.progress !== "" && stale.length === 0 &&
         /^primary rays /m.test(gr.stderr),
         "a render's progress: " + (gr.progress ? "\"" + gr.progress + "\" while it ran" : "none shown") +
         "; in the statistics: " + (stale.length ? JSON.stringify(stale) : "no progress line") +
         " (" + gr.state + ": " + gr.status + ")");

  const l = cases.long;
  const cancelled = await run({ chapter: l.chapter, scene: "", size: l.size, pixel: l.pixel,
                                text: l.text, cancelAfter: 500 });
  report(cancelled.before === "rendering" && cancelled.state === "cancelled" &&
         cancelled.after === "cancelled",
         "a long render: " + cancelled.before + " after 0.5 s, " + cancelled.state +
         " at once, still " + cancelled.after + " a second later");
  const again = await run({ chapter: l.chapter, scene: "", size: "8x6", text: l.text });
  report(again.state === "done", "after the cancel, a render: " + again.state);
}

// book_check.js's findings in the loaded page, taken out of it again:
// each problem a failure, then its summary.
async function layout(sessionId, view) {
  const lines = await inPage(sessionId, "function (script) { (0, eval)(script);" +
    " var report = document.getElementById('book-check-report');" +
    " if (!report) return []; var text = report.textContent; report.remove();" +
    " return text.split('\\n').filter(function (x) { return x; }); }",
    fs.readFileSync(view.script, "utf8"));
  const done = lines.filter((x) => x.startsWith("book-check: done, "));
  for (const x of lines.filter((y) => y.startsWith("book-check: problem: ")))
    report(false, "layout: " + x.slice("book-check: problem: ".length));
  report(done.length === 1, "layout at " + view.width + " x " + view.height + ": " +
         (done.length ? done[0].slice("book-check: done, ".length) : "the script did not finish"));
}

async function main() {
  const { targetId } = await send("Target.createTarget", { url: "about:blank" });
  const { sessionId } = await send("Target.attachToTarget", { targetId, flatten: true });
  if (cases.layout) { // the reader's window, as make book-check opens it
    await send("Emulation.setDeviceMetricsOverride", { width: cases.layout.width,
      height: cases.layout.height, deviceScaleFactor: 1, mobile: false }, sessionId);
    await send("Emulation.setScrollbarsHidden", { hidden: true }, sessionId);
  }
  const requests = [];
  listeners.push((m) => {
    if (m.method === "Network.requestWillBeSent" && m.sessionId === sessionId)
      requests.push(m.params.request.url);
  });
  await send("Network.enable", {}, sessionId);
  await send("Network.emulateNetworkConditions", { offline: true, latency: 0,
    downloadThroughput: -1, uploadThroughput: -1 }, sessionId);
  await send("Page.enable", {}, sessionId);
  const loaded = new Promise((resolve) => listeners.push((m) => {
    if (m.method === "Page.loadEventFired" && m.sessionId === sessionId) resolve();
  }));
  await send("Page.navigate", { url: "file://" + path.resolve(book) }, sessionId);
  await loaded;
  if (cases.speed) return speed(sessionId, cases.speed);
  if (cases.layout) await layout(sessionId, cases.layout);
  const run = (c) => inPage(sessionId, renderInPage.toString().replace("HELPERS;", PAGE_HELPERS), c);
  const count = await inPage(sessionId, "function () { return document.querySelectorAll('div.playground details').length; }");
  report(count > 0, count + " playgrounds in the page");

  // The renders run side by side, one a core (each playground has a worker
  // of its own); their lines are printed in the cases' order.
  const results = new Array(cases.renders.length);
  let next = 0;
  async function renderNext() {
    while (next < cases.renders.length) {
      const k = next++;
      results[k] = await run(cases.renders[k]);
    }
  }
  const lanes = Math.max(1, Math.min(os.cpus().length, 4));
  await Promise.all(Array.from({ length: lanes }, renderNext));
  let pixels = 0, differing = 0, largest = 0;
  for (const [k, c] of cases.renders.entries()) {
    const r = results[k];
    const what = "chapter " + c.chapter + " " + (c.scene || "(its own scene)") + " at " + c.size;
    if (r.state !== "done" || r.largest === undefined) {
      report(false, what + ": " + (r.error || r.state + ": " + r.status + " " +
             (r.width !== undefined ? r.width + "x" + r.height + " against " +
              r.referenceWidth + "x" + r.referenceHeight : "")));
      continue;
    }
    pixels += r.width * r.height; differing += r.differ;
    largest = Math.max(largest, r.largest);
    report(r.largest <= 1, what + ": " + r.differ + " of " + r.width * r.height +
           " pixels differ from bin/ch" + c.chapter + "'s, by " + r.largest + " code at most");
  }
  report(true, "renders: " + differing + " of " + pixels + " pixels differ, by " +
         largest + " code at most");

  const control = await run(cases.control);
  report(control.state === "done" && control.largest > 1,
         "the comparison can fail: chapter " + cases.control.chapter +
         "'s empty scene against one of its scenes: " +
         control.differ + " pixels differ, by " + control.largest + " codes at most");

  if (cases.mistake) await mistakes(run);
  if (cases.progress) await longRenders(run);

  if (process.env.PAGE_CHECK_SCREENSHOT) { // to look at: the last scene's playground
    const last = cases.renders[cases.renders.length - 1];
    await inPage(sessionId, "function (c) { var all = document.querySelectorAll('div.playground');" +
      " for (var i = 0; i < all.length; i++) if ((all[i].dataset.scene || '') === c.scene &&" +
      " +all[i].dataset.chapter === +c.chapter) all[i].scrollIntoView(); }", last);
    const shot = await send("Page.captureScreenshot", { format: "png" }, sessionId);
    fs.writeFileSync(process.env.PAGE_CHECK_SCREENSHOT, Buffer.from(shot.data, "base64"));
  }
  const outside = requests.filter((u) => !/^(file|data|blob):/.test(u));
  report(outside.length === 0, "network off: " + requests.length + " requests, " +
         (outside.length ? "outside the page: " + outside.join(" ") : "none outside the file"));
}

// The checks take well under a minute; the speed chart's rounds, minutes.
const timeout = setTimeout(() => {
  report(false, "timed out; the browser said: " + browserLog);
  chrome.kill();
  process.exit(1);
}, cases.speed ? 900000 : 140000);
// The browser's profile goes once the browser has gone.
function finish(status) {
  clearTimeout(timeout);
  chrome.on("exit", () => {
    try { fs.rmSync(profile, { recursive: true, force: true }); } catch (e) { /* tmp */ }
    process.exit(status);
  });
  chrome.kill();
}
main().then(() => finish(failures ? 1 : 0), (e) => {
  report(false, String(e) + "; the browser said: " + browserLog);
  finish(1);
});
