#!/usr/bin/env node
// Prints "KEY FILE" for each source file given: a hash of what clang-tidy's verdict on the
// file depends on (clang-tidy's version, .clang-tidy, the file's compile command with the
// checkout's path taken out, and its preprocessed text: every header it includes), so that
// tests/lint.sh runs clang-tidy only on files whose key has not passed before (as ccache does
// for compilers). A file that cannot be preprocessed gets no key and is always checked.
// Usage: node tests/tidy_keys.mjs build/lint/compile_commands.json FILE...
import { execFileSync, spawn } from 'node:child_process';
import { createHash } from 'node:crypto';
import { readFileSync, realpathSync } from 'node:fs';
import { availableParallelism } from 'node:os';
import { basename, dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = realpathSync(join(dirname(fileURLToPath(import.meta.url)), '..'));
const [dbPath, ...files] = process.argv.slice(2);
const entries = new Map(JSON.parse(readFileSync(dbPath, 'utf8')).map((e) => [realpathSync(e.file), e]));
const version = execFileSync('clang-tidy', ['--version'], { encoding: 'utf8' });
const config = readFileSync(join(root, '.clang-tidy'));
const sha = (x) => createHash('sha256').update(x).digest();

// The compile command's words (CMake writes plain words: no quoting beyond spaces).
const words = (command) => command.split(/\s+/).filter(Boolean);

function key(file) {
  let entry;
  try { entry = entries.get(realpathSync(join(root, file))); } catch { return Promise.resolve(null); }
  if (!entry || /["'\\]/.test(entry.command)) return Promise.resolve(null);
  const args = [];
  const all = words(entry.command);
  for (let i = 0; i < all.length; i++) {
    if (all[i] === '-o') { i++; continue; }  // no output file
    args.push(all[i] === '-c' ? '-E' : all[i]);
  }
  if (!args.includes('-E')) return Promise.resolve(null);
  args.splice(args.indexOf('-E') + 1, 0, '-P');  // no line markers: the text, not where it lies
  if (basename(args[0]) === 'ccache') args.shift();
  return new Promise((resolve) => {
    const p = spawn(args[0], args.slice(1), { cwd: entry.directory, stdio: ['ignore', 'pipe', 'ignore'] });
    const h = createHash('sha256');
    for (const part of [version, config, entry.command.split(root).join('<root>')]) h.update(sha(part));
    const text = createHash('sha256');
    p.stdout.on('data', (d) => text.update(d));
    p.on('error', () => resolve(null));
    p.on('close', (code) => {
      if (code !== 0) return resolve(null);
      h.update(text.digest());
      resolve(h.digest('hex'));
    });
  });
}

const keys = new Array(files.length).fill(null);
let next = 0;
async function worker() {
  while (next < files.length) {
    const i = next++;
    keys[i] = await key(files[i]);
  }
}
await Promise.all(Array.from({ length: availableParallelism() }, worker));
for (let i = 0; i < files.length; i++) if (keys[i]) console.log(`${keys[i]} ${files[i]}`);
