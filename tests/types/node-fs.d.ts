// The one node:fs function check.ts uses (no @types/node needed).
declare module 'node:fs' {
  export function readFileSync(path: URL, encoding: 'utf8'): string;
}
