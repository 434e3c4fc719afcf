/*
 * worker.js -- runs one chapter's program (WebAssembly, WASI preview 1) on
 * one scene, in a Web Worker of the book's page (tools/editions/page/playground.js
 * starts it from a Blob URL, so that the book works from file://).
 *
 * Message in:  { program, scene, sceneName, meshes, args }
 *   program    the chapter's .wasm, gzip, base64
 *   scene      the scene's text, at the path sceneName of a file system
 *              held here in memory ("." is its one preopened folder)
 *   meshes     [[name, gzip base64], ...]: files under meshes/ beside it
 *   args       the command line after the program's name
 * Messages out, while it runs: { progress }, the program's progress line
 * as it is redrawn (at most ten a second); at the end:
 *              { status, ms, stderr, picture }
 *   status     the program's exit status (-1: it trapped)
 *   ms         the run's wall time, load, build and render
 *   stderr     what it wrote there, without its progress lines: --stats,
 *              or its located error
 *   picture    { width, height, rgba } from standard output (the page's
 *              png.h writes the width, the height, then RGBA), or null
 *
 * Standard error is a terminal to the program: it redraws its progress
 * line in place, starting it with a carriage return, and such a line is
 * the progress, shown while it runs and not kept in stderr.
 *
 * The system is the least the programs need: arguments, clocks, reading
 * the in-memory files, writing standard output and error, exit. Every
 * other call answers ENOSYS; creating a file answers ENOTSUP.
 */
"use strict";

var ERRNO = { BADF: 8, INVAL: 28, NOENT: 44, NOSYS: 52, NOTDIR: 54, NOTSUP: 58 };
var FILETYPE = { UNKNOWN: 0, CHARACTER_DEVICE: 2, DIRECTORY: 3, REGULAR: 4 };
var RIGHT = { FD_SEEK: 1n << 2n, FD_TELL: 1n << 5n };
var ALL_RIGHTS = 0xffffffffffffffffn;
var PREOPEN_FD = 3;

function Exit(code) { this.code = code; }

async function gunzip(base64) {
  var raw = atob(base64), bytes = new Uint8Array(raw.length);
  for (var i = 0; i < raw.length; i++) bytes[i] = raw.charCodeAt(i);
  var stream = new Blob([bytes]).stream()
    .pipeThrough(new DecompressionStream("gzip"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

function concat(chunks) {
  var size = chunks.reduce(function (n, c) { return n + c.length; }, 0);
  var all = new Uint8Array(size), at = 0;
  chunks.forEach(function (c) { all.set(c, at); at += c.length; });
  return all;
}

// "a/./b/../c" as "a/c": the files are looked up by their plain path.
function normal(path) {
  var parts = [];
  path.split("/").forEach(function (p) {
    if (p === "" || p === ".") return;
    if (p === "..") parts.pop(); else parts.push(p);
  });
  return parts.join("/");
}

// The system calls, over files (a Map from plain path to bytes), with the
// output collected in out.stdout and out.stderr (lists of byte arrays).
function makeSystem(files, args, out) {
  var memory = null;
  var open = new Map();
  var nextFd = PREOPEN_FD + 1;
  var argBytes = args.map(function (a) { return new TextEncoder().encode(a + "\0"); });
  function view() { return new DataView(memory.buffer); }
  function bytes() { return new Uint8Array(memory.buffer); }
  function pathAt(ptr, len) {
    return new TextDecoder().decode(bytes().slice(ptr, ptr + len));
  }
  function isFolder(path) {
    var p = normal(path);
    if (p === "") return true;
    for (var name of files.keys()) if (name.startsWith(p + "/")) return true;
    return false;
  }
  function writeFilestat(ptr, type, size) {
    var v = view();
    for (var i = 0; i < 64; i += 8) v.setBigUint64(ptr + i, 0n, true);
    v.setUint8(ptr + 16, type);
    v.setBigUint64(ptr + 24, 1n, true);
    v.setBigUint64(ptr + 32, BigInt(size), true);
  }
  // Each iovec: a pointer and a length, 32 bits each.
  function eachBuffer(iovs, count, visit) {
    var v = view(), n = 0;
    for (var i = 0; i < count; i++) {
      var ptr = v.getUint32(iovs + 8 * i, true);
      var len = v.getUint32(iovs + 8 * i + 4, true);
      var done = visit(ptr, len);
      n += done;
      if (done < len) break;
    }
    return n;
  }
  var calls = {
    args_sizes_get: function (countPtr, sizePtr) {
      var size = argBytes.reduce(function (n, b) { return n + b.length; }, 0);
      view().setUint32(countPtr, argBytes.length, true);
      view().setUint32(sizePtr, size, true);
      return 0;
    },
    args_get: function (argvPtr, bufPtr) {
      argBytes.forEach(function (b, i) {
        view().setUint32(argvPtr + 4 * i, bufPtr, true);
        bytes().set(b, bufPtr);
        bufPtr += b.length;
      });
      return 0;
    },
    environ_sizes_get: function (countPtr, sizePtr) {
      view().setUint32(countPtr, 0, true);
      view().setUint32(sizePtr, 0, true);
      return 0;
    },
    environ_get: function () { return 0; },
    // Clock 0 is the calendar's; the others (monotonic, processor) the
    // page's own, in nanoseconds.
    clock_time_get: function (id, precision, ptr) {
      var ns = id === 0 ? BigInt(Date.now()) * 1000000n
                        : BigInt(Math.round(performance.now() * 1e6));
      view().setBigUint64(ptr, ns, true);
      return 0;
    },
    clock_res_get: function (id, ptr) {
      view().setBigUint64(ptr, 1000n, true);
      return 0;
    },
    fd_write: function (fd, iovs, count, writtenPtr) {
      if (fd !== 1 && fd !== 2) return ERRNO.BADF;
      var pieces = out.stderr.length;
      var n = eachBuffer(iovs, count, function (ptr, len) {
        (fd === 1 ? out.stdout : out.stderr).push(bytes().slice(ptr, ptr + len));
        return len;
      });
      if (fd === 2) out.onError(out.stderr.slice(pieces));
      view().setUint32(writtenPtr, n, true);
      return 0;
    },
    fd_read: function (fd, iovs, count, readPtr) {
      var f = open.get(fd);
      if (fd === 0) f = { data: new Uint8Array(0), pos: 0 };
      if (!f || !f.data) return ERRNO.BADF;
      var n = eachBuffer(iovs, count, function (ptr, len) {
        var part = f.data.subarray(f.pos, f.pos + len);
        bytes().set(part, ptr);
        f.pos += part.length;
        return part.length;
      });
      view().setUint32(readPtr, n, true);
      return 0;
    },
    fd_seek: function (fd, offset, whence, ptr) {
      var f = open.get(fd);
      if (!f || !f.data) return ERRNO.BADF;
      var base = whence === 0 ? 0 : whence === 1 ? f.pos : f.data.length;
      var pos = base + Number(offset);
      if (pos < 0) return ERRNO.INVAL;
      f.pos = pos;
      view().setBigUint64(ptr, BigInt(pos), true);
      return 0;
    },
    fd_close: function (fd) { return open.delete(fd) ? 0 : ERRNO.BADF; },
    // Standard input and output are of no known type: not a terminal, so
    // that the program writes its picture. Standard error is a terminal
    // (a character device that cannot seek), where the program redraws
    // its progress line in place.
    fd_fdstat_get: function (fd, ptr) {
      var f = fd === PREOPEN_FD ? { folder: true } : open.get(fd);
      if (fd > 2 && !f) return ERRNO.BADF;
      var type = fd === 2 ? FILETYPE.CHARACTER_DEVICE
               : fd <= 2 ? FILETYPE.UNKNOWN
               : f.folder ? FILETYPE.DIRECTORY : FILETYPE.REGULAR;
      var rights = fd === 2 ? ALL_RIGHTS & ~(RIGHT.FD_SEEK | RIGHT.FD_TELL)
                            : ALL_RIGHTS;
      var v = view();
      v.setUint8(ptr, type);
      v.setUint16(ptr + 2, 0, true);
      v.setBigUint64(ptr + 8, rights, true);
      v.setBigUint64(ptr + 16, rights, true);
      return 0;
    },
    fd_fdstat_set_flags: function () { return 0; },
    fd_filestat_get: function (fd, ptr) {
      var f = fd === PREOPEN_FD ? { folder: true } : open.get(fd);
      if (fd <= 2) { writeFilestat(ptr, FILETYPE.UNKNOWN, 0); return 0; }
      if (!f) return ERRNO.BADF;
      writeFilestat(ptr, f.folder ? FILETYPE.DIRECTORY : FILETYPE.REGULAR,
                    f.folder ? 0 : f.data.length);
      return 0;
    },
    fd_prestat_get: function (fd, ptr) {
      if (fd !== PREOPEN_FD) return ERRNO.BADF;
      view().setUint8(ptr, 0);
      view().setUint32(ptr + 4, 1, true);
      return 0;
    },
    fd_prestat_dir_name: function (fd, ptr) {
      if (fd !== PREOPEN_FD) return ERRNO.BADF;
      bytes()[ptr] = 46; /* "." */
      return 0;
    },
    path_open: function (dirFd, lookup, pathPtr, pathLen, oflags,
                         rights, inheriting, fdflags, fdPtr) {
      var CREATE = 1, DIRECTORY = 2, EXCLUSIVE = 4, TRUNCATE = 8;
      if (oflags & (CREATE | EXCLUSIVE | TRUNCATE)) return ERRNO.NOTSUP;
      var path = pathAt(pathPtr, pathLen);
      var data = files.get(normal(path));
      if (data === undefined && !isFolder(path)) return ERRNO.NOENT;
      if ((oflags & DIRECTORY) && data !== undefined) return ERRNO.NOTDIR;
      var fd = nextFd++;
      open.set(fd, data === undefined ? { folder: true } : { data: data, pos: 0 });
      view().setUint32(fdPtr, fd, true);
      return 0;
    },
    path_filestat_get: function (dirFd, lookup, pathPtr, pathLen, ptr) {
      var path = pathAt(pathPtr, pathLen);
      var data = files.get(normal(path));
      if (data === undefined && !isFolder(path)) return ERRNO.NOENT;
      writeFilestat(ptr, data === undefined ? FILETYPE.DIRECTORY : FILETYPE.REGULAR,
                    data === undefined ? 0 : data.length);
      return 0;
    },
    random_get: function (ptr, len) {
      for (var at = 0; at < len; at += 65536)
        crypto.getRandomValues(bytes().subarray(ptr + at, ptr + Math.min(len, at + 65536)));
      return 0;
    },
    sched_yield: function () { return 0; },
    proc_exit: function (code) { throw new Exit(code); },
  };
  var imports = new Proxy(calls, {
    get: function (target, name) {
      return target[name] || function () { return ERRNO.NOSYS; };
    },
  });
  return { imports: imports, setMemory: function (m) { memory = m; } };
}

// The picture on standard output: width and height, then RGBA.
function pictureOf(stdout) {
  if (stdout.length < 8) return null;
  var v = new DataView(stdout.buffer, stdout.byteOffset, 8);
  var width = v.getUint32(0, true), height = v.getUint32(4, true);
  if (stdout.length !== 8 + 4 * width * height) return null;
  return { width: width, height: height, rgba: stdout.slice(8) };
}

async function filesOf(job) {
  var files = new Map();
  var folder = job.sceneName.replace(/[^/]*$/, "");
  files.set(normal(job.sceneName), new TextEncoder().encode(job.scene));
  for (var [name, base64] of job.meshes)
    files.set(normal(folder + "meshes/" + name), await gunzip(base64));
  return files;
}

// Standard error as a terminal leaves it: a line that was redrawn in
// place (it holds a carriage return) was the progress, and goes.
function withoutProgress(text) {
  return text.split("\n").filter(function (line) {
    return line.indexOf("\r") < 0;
  }).join("\n");
}

// The progress line being drawn now: what follows the last carriage
// return of the last line, if that line has one.
function progressOf(text) {
  var line = text.slice(text.lastIndexOf("\n") + 1);
  var at = line.lastIndexOf("\r");
  return at < 0 ? null : line.slice(at + 1).trim();
}

async function run(job) {
  var files = await filesOf(job);
  var module = await WebAssembly.compile(await gunzip(job.program));
  var out = { stdout: [], stderr: [] };
  var said = "", posted = 0, decoder = new TextDecoder();
  out.onError = function (pieces) { // the progress, ten a second at most
    pieces.forEach(function (p) { said += decoder.decode(p, { stream: true }); });
    var line = progressOf(said), now = performance.now();
    if (line && now - posted >= 100) {
      posted = now;
      postMessage({ progress: line });
    }
  };
  var system = makeSystem(files, ["program"].concat(job.args), out);
  var instance = await WebAssembly.instantiate(module, { wasi_snapshot_preview1: system.imports });
  system.setMemory(instance.exports.memory);
  var start = performance.now(), status = 0;
  try {
    instance.exports._start();
  } catch (e) {
    if (e instanceof Exit) status = e.code;
    else { status = -1; out.stderr.push(new TextEncoder().encode(String(e) + "\n")); }
  }
  var ms = performance.now() - start;
  var picture = status === 0 ? pictureOf(concat(out.stdout)) : null;
  var stderr = withoutProgress(new TextDecoder().decode(concat(out.stderr)));
  postMessage({ status: status, ms: ms, stderr: stderr, picture: picture },
              picture ? [picture.rgba.buffer] : []);
}

onmessage = function (event) {
  run(event.data).catch(function (e) {
    postMessage({ status: -1, ms: 0, stderr: String(e) + "\n", picture: null });
  });
};
