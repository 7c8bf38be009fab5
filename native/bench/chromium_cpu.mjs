// CPU ms (utime + stime of /proc/PID/stat, all threads, exited threads included) of the
// Chromium processes started with --type=<type> (e.g. 'gpu-process', 'renderer'): what the
// page benches charge to the GPU process or the page besides wall time.
import { readFileSync, readdirSync } from 'node:fs';

const tickMs = 1000 / 100;  // USER_HZ

export function chromiumCpuMs(type) {
  let ms = 0;
  for (const pid of readdirSync('/proc').filter((d) => /^\d+$/.test(d))) {
    try {
      if (!readFileSync(`/proc/${pid}/cmdline`, 'utf8').includes(`--type=${type}`)) continue;
      const f = readFileSync(`/proc/${pid}/stat`, 'utf8').split(') ')[1].split(' ');
      ms += (Number(f[11]) + Number(f[12])) * tickMs;
    } catch { /* gone */ }
  }
  return ms;
}
