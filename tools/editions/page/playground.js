/*
 * playground.js -- "edit and render" under the book's scenes.
 *
 * tools/book/weave.lua leaves an empty <div class="playground"> after every
 * scenes/*.scene file the chapters show (data-scene: its name) and one at
 * the end of every chapter (no data-scene: an empty scene to write), with
 * the chapter's number in data-chapter. tools/editions/page.sh puts this script in
 * the page with the programs, gzip and base64, in
 * <script type="application/octet-stream" id="rt-program-NN">, the meshes
 * in <script ... class="rt-mesh" data-name="NAME">, and the worker's code
 * (tools/editions/page/worker.js) in <script type="text/plain" id="rt-worker">.
 *
 * Each playground whose chapter has a program gets an editor, the --size
 * and --pixel settings (the latter from chapter 13, which adds it), Render
 * and Cancel buttons, a status line, the picture and the --stats counts.
 * A render runs in a new worker, which Cancel ends; the status line shows
 * the time and the program's progress line while it runs, and an error
 * where it is (in the editor, or in the --pixel box). The playground's
 * data-state says where it is: idle, rendering, done, error, cancelled
 * (the browser checks, tools/checks/page_check.js, read it).
 */
(function () {
  "use strict";

  var workerUrl = null;

  function workerURL() {
    if (!workerUrl) {
      var code = document.getElementById("rt-worker").textContent;
      workerUrl = URL.createObjectURL(new Blob([code], { type: "text/javascript" }));
    }
    return workerUrl;
  }

  function element(tag, className, text) {
    var e = document.createElement(tag);
    if (className) e.className = className;
    if (text) e.textContent = text;
    return e;
  }

  function two(number) { return ("0" + number).slice(-2); }

  // The scene's text as the book shows it, from the code box just before.
  function sceneText(div) {
    var name = div.dataset.scene;
    if (!name) return "";
    for (var e = div.previousElementSibling; e; e = e.previousElementSibling) {
      if (e.dataset && e.dataset.file === name) {
        var pre = e.querySelector("pre");
        return pre ? pre.textContent.replace(/\n*$/, "\n") : "";
      }
    }
    return "";
  }

  function meshesOf(text) {
    var wanted = {}, meshes = [];
    (text.match(/meshes\/[A-Za-z0-9._-]+/g) || []).forEach(function (m) {
      wanted[m.slice("meshes/".length)] = true;
    });
    document.querySelectorAll("script.rt-mesh").forEach(function (s) {
      if (wanted[s.dataset.name]) meshes.push([s.dataset.name, s.textContent.trim()]);
    });
    return meshes;
  }

  // "scenes/x.scene:3:7: error: what": the name (the scene's file, a
  // mesh's, or an option: --pixel), the line, the column and the message.
  function located(stderr) {
    var m = /^([^\n]*?):(\d+):(\d+): error: ([^\n]*)$/m.exec(stderr);
    return m ? { name: m[1], line: +m[2], column: +m[3], message: m[4], text: m[0] } : null;
  }

  function selectAt(editor, line, column) {
    var lines = editor.value.split("\n"), at = 0;
    for (var i = 0; i < line - 1 && i < lines.length; i++) at += lines[i].length + 1;
    var end = at + (lines[line - 1] || "").length;
    var start = Math.min(at + Math.max(column - 1, 0), end);
    editor.focus();
    editor.setSelectionRange(start, end);
  }

  function drawPicture(canvas, picture) {
    canvas.width = picture.width;
    canvas.height = picture.height;
    var pixels = new ImageData(new Uint8ClampedArray(picture.rgba.buffer),
                               picture.width, picture.height);
    canvas.getContext("2d").putImageData(pixels, 0, 0);
    canvas.hidden = false;
  }

  function setUp(div) {
    var chapter = two(div.dataset.chapter);
    var program = document.getElementById("rt-program-" + chapter);
    if (!program) return;
    var sceneName = div.dataset.scene || "scenes/yours.scene";
    var ui = {};
    var summary = element("summary", null, div.dataset.scene
      ? "Edit and render " + div.dataset.scene + " with chapter " + (+chapter) + "'s program"
      : "Write a scene and render it with chapter " + (+chapter) + "'s program");
    var details = element("details");
    details.appendChild(summary);
    ui.editor = element("textarea", "playground-editor");
    ui.editor.value = sceneText(div);
    ui.editor.rows = Math.min(Math.max(ui.editor.value.split("\n").length, 4), 24);
    ui.editor.spellcheck = false;
    ui.editor.setAttribute("aria-label", "scene");
    details.appendChild(ui.editor);
    var settings = element("div", "playground-settings");
    ui.size = element("input");
    ui.size.placeholder = "the scene's";
    ui.size.size = 10;
    settings.appendChild(labelled("--size", ui.size));
    if (+chapter >= 13) {
      ui.pixel = element("input");
      ui.pixel.placeholder = "e.g. pattern jittered samples 4";
      ui.pixel.size = 28;
      settings.appendChild(labelled("--pixel", ui.pixel));
    }
    ui.render = element("button", "playground-render", "Render");
    ui.cancel = element("button", "playground-cancel", "Cancel");
    ui.cancel.disabled = true;
    settings.appendChild(ui.render);
    settings.appendChild(ui.cancel);
    details.appendChild(settings);
    ui.status = element("div", "playground-status");
    details.appendChild(ui.status);
    ui.canvas = element("canvas", "playground-picture");
    ui.canvas.hidden = true;
    details.appendChild(ui.canvas);
    ui.stats = element("pre", "playground-stats");
    ui.stats.hidden = true;
    details.appendChild(ui.stats);
    div.appendChild(details);
    div.dataset.state = "idle";
    var job = { worker: null, timer: 0, started: 0 };
    ui.render.addEventListener("click", function () { render(div, ui, job, program, sceneName); });
    ui.cancel.addEventListener("click", function () { cancel(div, ui, job); });
  }

  function labelled(name, input) {
    var label = element("label");
    label.appendChild(element("code", null, name));
    label.appendChild(document.createTextNode(" "));
    label.appendChild(input);
    return label;
  }

  function argumentsOf(ui, sceneName) {
    var args = [sceneName, "-o", "-", "--stats"];
    if (ui.size.value.trim()) args.push("--size", ui.size.value.trim());
    if (ui.pixel && ui.pixel.value.trim()) args.push("--pixel", ui.pixel.value.trim());
    return args;
  }

  function stop(job) {
    if (job.worker) job.worker.terminate();
    clearInterval(job.timer);
    job.worker = null;
  }

  function seconds(ms) { return (ms / 1000).toFixed(ms < 10000 ? 2 : 1) + " s"; }

  function render(div, ui, job, program, sceneName) {
    stop(job);
    var worker = new Worker(workerURL());
    job.worker = worker;
    job.started = performance.now();
    div.dataset.state = "rendering";
    ui.status.className = "playground-status";
    ui.status.textContent = "rendering…";
    ui.cancel.disabled = false;
    job.progress = "";
    job.timer = setInterval(function () {
      ui.status.textContent = "rendering… " + seconds(performance.now() - job.started) +
        (job.progress ? " — " + job.progress : "");
    }, 250);
    worker.onmessage = function (event) {
      if (job.worker !== worker) return;
      if (event.data.progress !== undefined) { job.progress = event.data.progress; return; }
      stop(job);
      ui.cancel.disabled = true;
      show(div, ui, event.data, sceneName);
    };
    worker.postMessage({ program: program.textContent.trim(), scene: ui.editor.value,
                         sceneName: sceneName, meshes: meshesOf(ui.editor.value),
                         args: argumentsOf(ui, sceneName) });
  }

  // Where an error is: in the scene's text, a line and a column selected
  // in the editor; in the --pixel box (one line), its column there; in
  // another file (a mesh), only said.
  function showError(ui, error, sceneName) {
    if (error.name === sceneName) {
      selectAt(ui.editor, error.line, error.column);
      return "line " + error.line + ", column " + error.column + ": " + error.message;
    }
    if (error.name === "--pixel" && ui.pixel) {
      ui.pixel.focus();
      ui.pixel.setSelectionRange(Math.max(error.column - 1, 0), ui.pixel.value.length);
      return "--pixel, column " + error.column + ": " + error.message;
    }
    return error.name + ", line " + error.line + ", column " + error.column + ": " + error.message;
  }

  function show(div, ui, result, sceneName) {
    var error = result.status !== 0 ? located(result.stderr) : null;
    ui.stats.textContent = result.stderr;
    ui.stats.hidden = result.stderr === "";
    if (result.status !== 0) {
      div.dataset.state = "error";
      ui.status.className = "playground-status playground-error";
      ui.status.textContent = error ? showError(ui, error, sceneName)
        : (result.stderr.trim().split("\n")[0] || "the program stopped (status " + result.status + ")");
      return;
    }
    div.dataset.state = "done";
    if (result.picture) drawPicture(ui.canvas, result.picture);
    ui.status.textContent = (result.picture ? result.picture.width + " × " + result.picture.height
      + " pixels in " : "done in ") + seconds(result.ms) + " (one thread)";
  }

  function cancel(div, ui, job) {
    if (!job.worker) return;
    stop(job);
    ui.cancel.disabled = true;
    div.dataset.state = "cancelled";
    ui.status.className = "playground-status";
    ui.status.textContent = "cancelled after " + seconds(performance.now() - job.started);
  }

  function start() {
    if (!window.Worker || !window.WebAssembly || !window.DecompressionStream) return;
    document.querySelectorAll("div.playground").forEach(setUp);
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
