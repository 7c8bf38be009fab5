#!/usr/bin/env node
// The package's command line (`npx anisomesh ...`), behaving like the native CLI:
//   anisomesh mesh CASE.json -o OUT [--quads] [--all-quads] [--stats] [--max-elements N] [--no-updates]
//   anisomesh remesh IN.mesh -sol IN.sol -o OUT [-hgrad R] [-hmin H] [-hmax H] [--stats] [--max-elements N]
// OUT: .mesh, .vtk, .obj or .svg. --stats prints one JSON object. Errors: stderr
// "anisomesh: error CODE: message", exit 1 (bad input) or 2 (bad usage); the output
// file is written atomically (never partial).
import { readFileSync, renameSync, rmSync, writeFileSync } from 'node:fs';
import { basename, dirname, extname, join } from 'node:path';
import { loadAnisomesh, AnisomeshError } from './node.js';

const usage = `usage: anisomesh <command> [options]
commands:
  mesh CASE.json -o OUT [--quads] [--all-quads] [--stats] [--max-elements N] [--no-updates]
                            mesh a JSON case, planar or surface (OUT: .mesh, .vtk, .obj or .svg)
  remesh IN.mesh -sol IN.sol -o OUT [-hgrad R] [-hmin H] [-hmax H] [--stats] [--max-elements N]
                            remesh the domain of IN.mesh under the metric IN.sol
  --version                 print the version
--stats prints one JSON object on stdout. Errors: exit 1 (bad input), 2 (bad usage).
`;

class UsageError extends Error {}

function formatOf(path) {
  const ext = extname(path).slice(1).toLowerCase();
  if (!['mesh', 'vtk', 'obj', 'svg'].includes(ext)) throw new UsageError(`output '${path}': expected a .mesh, .vtk, .obj or .svg file`);
  return ext;
}

function readInput(path) {
  try {
    return readFileSync(path, 'utf8');
  } catch (e) {
    throw new AnisomeshError('IO_ERROR', `cannot read '${path}': ${e.code ?? e.message}`);
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

function parseArgs(argv, flags, valued) {
  const out = { positional: [] };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (flags.includes(a)) out[a] = true;
    else if (valued.includes(a)) {
      if (i + 1 >= argv.length) throw new UsageError(`${a} expects a value`);
      out[a] = argv[++i];
    } else if (a.startsWith('-')) throw new UsageError(`unknown option '${a}'`);
    else out.positional.push(a);
  }
  return out;
}

function number(option, text, { integer = false } = {}) {
  const v = Number(text);
  if (!Number.isFinite(v) || v < 0 || (integer && (!Number.isInteger(v) || v <= 0))) {
    throw new UsageError(`${option} expects a ${integer ? 'positive integer' : 'nonnegative number'}, got '${text}'`);
  }
  return v;
}

async function main(argv) {
  const [command, ...rest] = argv;
  if (!command) throw new UsageError('missing command');
  if (command === '--help' || command === '-h') { process.stdout.write(usage); return 0; }
  const am = await loadAnisomesh();
  if (command === '--version') { console.log(`anisomesh ${am.version}`); return 0; }
  if (command === 'mesh') {
    const a = parseArgs(rest, ['--quads', '--all-quads', '--stats', '--no-updates'], ['-o', '--output', '--max-elements']);
    if (a.positional.length !== 1) throw new UsageError(a.positional.length ? `unexpected argument '${a.positional[1]}'` : 'missing CASE.json');
    const out = a['-o'] ?? a['--output'];
    if (!out) throw new UsageError('missing -o OUT');
    const format = formatOf(out);
    const options = {};
    if (a['--quads']) options.quads = true;
    if (a['--all-quads']) options.allQuads = true;
    if (a['--no-updates']) options.controlSpaceUpdates = false;
    if (a['--max-elements']) options.maxElements = number('--max-elements', a['--max-elements'], { integer: true });
    const { mesh, stats } = am.meshCase(readInput(a.positional[0]), options);
    writeAtomic(out, am.writeMesh(mesh, format));
    if (a['--stats']) console.log(JSON.stringify(stats));
    return 0;
  }
  if (command === 'remesh') {
    const a = parseArgs(rest, ['--stats'], ['-o', '--output', '-sol', '--sol', '-hgrad', '-hmin', '-hmax', '--max-elements']);
    if (a.positional.length !== 1) throw new UsageError('expected one input mesh');
    const out = a['-o'] ?? a['--output'], sol = a['-sol'] ?? a['--sol'];
    if (!out) throw new UsageError('missing -o OUT');
    if (!sol) throw new UsageError('missing -sol IN.sol');
    const format = formatOf(out);
    const input = am.readMesh(readInput(a.positional[0]), 'mesh');
    const metrics = am.readSol(readInput(sol), input.vertices.length / input.dimension);
    const options = {};
    for (const k of ['hgrad', 'hmin', 'hmax']) if (a[`-${k}`] !== undefined) options[k] = number(`-${k}`, a[`-${k}`]);
    if (a['--max-elements']) options.maxElements = number('--max-elements', a['--max-elements'], { integer: true });
    const { mesh, stats } = am.remesh(input, metrics, options);
    writeAtomic(out, am.writeMesh(mesh, format));
    if (a['--stats']) console.log(JSON.stringify(stats));
    return 0;
  }
  throw new UsageError(`unknown command '${command}'`);
}

main(process.argv.slice(2)).then((code) => { process.exitCode = code; }, (e) => {
  if (e instanceof UsageError) {
    process.stderr.write(`anisomesh: ${e.message}\n${usage}`);
    process.exitCode = 2;
  } else if (e instanceof AnisomeshError) {
    process.stderr.write(`anisomesh: error ${e.code}: ${e.message}\n`);
    process.exitCode = 1;
  } else {
    process.stderr.write(`anisomesh: error INTERNAL: ${e?.message ?? e}\n`);
    process.exitCode = 1;
  }
});
