#!/usr/bin/env node
// The package's command line (`npx anisomesh ...`): the native CLI's commands, options, usage
// text, exit codes and output bytes (tests/node/cli-parity.test.mjs runs both on every
// option). Errors: stderr "anisomesh: error CODE: message", exit 1 (bad input), or
// "anisomesh: usage error: ..." and the usage, exit 2; outputs are written atomically.
import { readFileSync, renameSync, rmSync, writeFileSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';
import { loadAnisomesh, AnisomeshError } from './node.js';

// Byte for byte the native usage (native/cli/*_command.cpp, main.cpp).
const usage = `usage: anisomesh <command> [options]
commands:
  mesh CASE.json -o OUT [--quads] [--all-quads] [--stats] [--max-elements N] [--no-updates] [-v N]
                            mesh a JSON case, planar or surface (OUT: .mesh, .vtk, .obj, .msh, .vtu or .svg;
                            -in CASE.json / -out OUT as in MMG; -v 1: progress on stderr)
      [--svg-uv] [--svg-view AZ,EL] [--svg-control-space]
                            .svg of a surface: 3D view from azimuth AZ, elevation EL (degrees;
                            default -63,34), or the parameter plane; control-space ellipses over it
  remesh IN.mesh [-sol IN.sol] -o OUT [-hgrad R] [-hmin H] [-hmax H] [-hsiz H] [-v N] [--stats]
         [--max-elements N]
                            remesh the domain of IN.mesh (or .msh, .vtk, .obj) under the metric IN.sol, as
                            a background-mesh control space (-hgrad: gradation ratio dr >= 1,
                            -1 or 0: off); without -sol: isotropic sizes, -hsiz H everywhere or
                            the input's edge lengths clamped to [-hmin, -hmax]; -in / -out as in MMG
  metric ALPHA H1 H2        print the metric tensor for sizes (h1, h2) at angle ALPHA (radians)
  --version                 print the version
--stats prints one JSON object on stdout. Errors: exit 1 (bad input), 2 (bad usage).
`;

class UsageError extends Error {}

// strtod's decimal syntax, whole string (as the native parse* helpers accept).
const numberSyntax = /^[ \t\n\v\f\r]*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?$/;
const toNumber = (text) => (numberSyntax.test(text) ? Number(text.trim()) : NaN);

function parseSignedNumber(option, text) {
  const v = toNumber(text);
  if (!Number.isFinite(v) || Math.abs(v) > 1e300) throw new UsageError(`${option} expects a number, got '${text}'`);
  return v;
}
function parseNumber(option, text) {
  const v = toNumber(text);
  if (!(v >= 0) || v > 1e300) throw new UsageError(`${option} expects a nonnegative number, got '${text}'`);
  return v;
}
function parseCount(option, text) {
  if (!/^[ \t\n\v\f\r]*[+-]?\d+$/.test(text) || !(Number(text.trim()) > 0)) {
    throw new UsageError(`${option} expects a positive integer, got '${text}'`);
  }
  return Number(text.trim());
}
function parseView(option, text) {
  const comma = text.indexOf(',');
  const az = comma < 0 ? NaN : toNumber(text.slice(0, comma));
  const el = comma < 0 ? NaN : toNumber(text.slice(comma + 1));
  if (!Number.isFinite(az) || !Number.isFinite(el)) {
    throw new UsageError(`${option} expects AZIMUTH,ELEVATION in degrees, got '${text}'`);
  }
  return [az, el];
}

function extension(path) {
  const slash = Math.max(path.lastIndexOf('/'), path.lastIndexOf('\\'));
  const dot = path.lastIndexOf('.');
  return dot < 0 || dot < slash ? '' : path.slice(dot + 1).toLowerCase();
}
const meshFormats = ['mesh', 'vtk', 'obj', 'msh'];
function requireOutput(out) {
  if (!out) throw new UsageError('missing -o OUT');
  if (['svg', 'vtu'].includes(extension(out)) || meshFormats.includes(extension(out))) return extension(out);
  throw new UsageError(`unknown mesh format of '${out}': expected the extension .mesh, .vtk, .obj or .msh (or .vtu, .svg)`);
}

function readInput(path) {
  try {
    return readFileSync(path, 'utf8');
  } catch (e) {
    throw new AnisomeshError('IO_ERROR', `cannot open '${path}' for reading: ${e.code ?? e.message}`);
  }
}

// Same folder, then rename: a failed run leaves no partial file.
function writeAtomic(path, text) {
  const tmp = join(dirname(path), `.${basename(path)}.${process.pid}.tmp`);
  try {
    writeFileSync(tmp, text);
    renameSync(tmp, path);
  } catch (e) {
    rmSync(tmp, { force: true });
    throw new AnisomeshError('IO_ERROR', `cannot write '${path}': ${e.code ?? e.message}`);
  }
}

// -v N >= 1: "anisomesh: NN%" lines on stderr, as the native progressPrinter.
function progressPrinter(verbosity) {
  if (verbosity < 1) return undefined;
  let last = -1;
  return (fraction) => {
    const percent = Math.floor(100 * fraction);
    if (percent >= last + 10 || (percent === 100 && last !== 100)) {
      process.stderr.write(`anisomesh: ${percent}%\n`);
      last = percent;
    }
    return true;
  };
}

async function runMesh(am, args) {
  let input = '', output = '', stats = false, glyphs = false, verbosity = 0;
  const options = {}, svg = {};
  for (let i = 0; i < args.length;) {
    const a = args[i++];
    const value = () => {
      if (i >= args.length) throw new UsageError(`${a} expects a value`);
      return args[i++];
    };
    if (a === '-o' || a === '--output' || a === '-out') output = value();
    else if (a === '-in') input = value();
    else if (a === '-v') verbosity = Math.trunc(parseSignedNumber(a, value()));
    else if (a === '--svg-uv') svg.uv = true;
    else if (a === '--svg-control-space') glyphs = true;
    else if (a === '--svg-view') svg.view = parseView(a, value());
    else if (a === '--quads') options.quads = true;
    else if (a === '--all-quads') options.allQuads = true;
    else if (a === '--stats') stats = true;
    else if (a === '--no-updates') options.controlSpaceUpdates = false;
    else if (a === '--max-elements') options.maxElements = parseCount(a, value());
    else if (a.startsWith('-')) throw new UsageError(`unknown option '${a}' for mesh`);
    else if (!input) input = a;
    else throw new UsageError(`unexpected argument '${a}'`);
  }
  if (!input) throw new UsageError('missing CASE.json');
  const format = requireOutput(output);
  if (format === 'svg') options.svg = { ...svg, controlSpace: glyphs };
  if (format === 'vtu') options.vtu = true;
  const progress = progressPrinter(verbosity);
  if (progress) options.onProgress = progress;
  const r = am.meshCase(readInput(input), options);
  writeAtomic(output, format === 'svg' ? r.svg : format === 'vtu' ? r.vtu : am.writeMesh(r.mesh, format));
  if (stats) console.log(JSON.stringify(r.stats));
  return 0;
}

async function runRemesh(am, args) {
  let input = '', sol = '', output = '', stats = false, verbosity = 0;
  const options = {};
  for (let i = 0; i < args.length;) {
    const a = args[i++];
    const value = () => {
      if (i >= args.length) throw new UsageError(`${a} expects a value`);
      return args[i++];
    };
    if (a === '-o' || a === '--output' || a === '-out') output = value();
    else if (a === '-in') input = value();
    else if (a === '-sol' || a === '--sol') sol = value();
    else if (a === '-hgrad' || a === '--hgrad') {
      const r = parseSignedNumber(a, value());
      if (r === -1) options.hgrad = 0;
      else if (r < 0 || (r > 0 && r < 1)) throw new UsageError(`${a} expects a ratio >= 1, 0 or -1 (off)`);
      else options.hgrad = r;
    } else if (a === '-hmin' || a === '--hmin') options.hmin = parseNumber(a, value());
    else if (a === '-hmax' || a === '--hmax') options.hmax = parseNumber(a, value());
    else if (a === '-hsiz' || a === '--hsiz') {
      options.hsiz = parseNumber(a, value());
      if (!(options.hsiz > 0)) throw new UsageError(`${a} expects a positive size`);
    } else if (a === '-v') verbosity = Math.trunc(parseSignedNumber(a, value()));
    else if (a === '--stats') stats = true;
    else if (a === '--max-elements') options.maxElements = parseCount(a, value());
    else if (a.startsWith('-')) throw new UsageError(`unknown option '${a}' for remesh`);
    else if (!input) input = a;
    else throw new UsageError(`unexpected argument '${a}'`);
  }
  if (!input) throw new UsageError('missing IN.mesh');
  if (!sol && !options.hsiz && !options.hmin && !options.hmax) {
    throw new UsageError('missing -sol IN.sol (or -hsiz H, -hmin H, -hmax H for isotropic sizes)');
  }
  if (sol && options.hsiz > 0) throw new UsageError('-hsiz and -sol exclude each other');
  const format = requireOutput(output);
  if (options.hmin > 0 && options.hmax > 0 && options.hmin > options.hmax) throw new UsageError('-hmin must not exceed -hmax');
  if (format === 'svg') options.svg = true;
  if (format === 'vtu') options.vtu = true;
  const progress = progressPrinter(verbosity);
  if (progress) options.onProgress = progress;
  const inFormat = extension(input);
  if (!meshFormats.includes(inFormat)) {
    throw new AnisomeshError('INVALID_ARGUMENT', `unknown mesh format of '${input}': expected the extension .mesh, .vtk, .obj or .msh`);
  }
  const mesh = am.readMesh(readInput(input), inFormat);
  const metrics = sol ? am.readSol(readInput(sol), mesh.vertices.length / mesh.dimension) : null;
  const r = am.remesh(mesh, metrics, options);
  writeAtomic(output, format === 'svg' ? r.svg : format === 'vtu' ? r.vtu : am.writeMesh(r.mesh, format));
  if (stats) console.log(JSON.stringify(r.stats));
  return 0;
}

async function runMetric(am, args) {
  const names = ['ALPHA', 'H1', 'H2'];
  const v = [];
  for (const a of args) {
    if (v.length === 3) throw new UsageError(`unexpected argument '${a}'`);
    v.push(parseSignedNumber(names[v.length], a));
  }
  if (v.length !== 3) throw new UsageError('metric expects ALPHA H1 H2');
  const m = am.metric({ alpha: v[0], h1: v[1], h2: v[2] });
  console.log(JSON.stringify({ m11: m.m11, m12: m.m12, m22: m.m22 }));
  return 0;
}

const commands = { mesh: runMesh, remesh: runRemesh, metric: runMetric };

async function main(argv) {
  const [command, ...rest] = argv;
  if (!command) { process.stderr.write(usage); return 2; }
  if (command === '--help' || command === '-h') { process.stdout.write(usage); return 0; }
  const run = Object.hasOwn(commands, command) ? commands[command] : null;
  if (command !== '--version' && !run) {
    process.stderr.write(`anisomesh: unknown command '${command}'\n${usage}`);
    return 2;
  }
  const am = await loadAnisomesh();
  if (command === '--version') { console.log(`anisomesh ${am.version}`); return 0; }
  return run(am, rest);
}

main(process.argv.slice(2)).then((code) => { process.exitCode = code; }, (e) => {
  if (e instanceof UsageError) {
    process.stderr.write(`anisomesh: usage error: ${e.message}\n${usage}`);
    process.exitCode = 2;
  } else if (e instanceof AnisomeshError) {
    process.stderr.write(`anisomesh: error ${e.code}: ${e.message}\n`);
    process.exitCode = 1;
  } else {
    process.stderr.write(`anisomesh: error INTERNAL: ${e?.message ?? e}\n`);
    process.exitCode = 1;
  }
});
