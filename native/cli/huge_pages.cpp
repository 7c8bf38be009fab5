// Memory setup of the CLI (freed memory kept for reuse: keepFreedMemory, below) and
// transparent huge pages for its heap. The meshing stages allocate and touch hundreds
// of MiB in large vectors; with 4 KiB pages each first touch is a page fault (110k of them
// in a 1e6-triangle remesh, a third of its CPU time on a virtual machine). glibc's malloc
// asks the kernel for 2 MiB pages when GLIBC_TUNABLES holds glibc.malloc.hugetlb=1, a
// tunable read only when the process starts: so the CLI starts itself again with it, once.
#include "cli.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#include <unistd.h>
#endif

namespace anisomesh::cli {

namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb";

// The kernel gives huge pages to a process that asks (THP "always" or "madvise", not "never").
bool kernelOffersHugePages() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(in, line) && line.find("[never]") == std::string::npos;
}

}  // namespace

void restartWithHugePages(char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  // Already set, by the first start or by the user (glibc.malloc.hugetlb=0 keeps them off).
  if (tunables && std::strstr(tunables, kTunable)) return;
  if (!kernelOffersHugePages()) return;
  const std::string value = std::string(tunables && *tunables ? std::string(tunables) + ":" : "") + kTunable + "=1";
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // No /proc, or exec refused: go on in this process, with 4 KiB pages.
  unsetenv("GLIBC_TUNABLES");
  if (tunables) setenv("GLIBC_TUNABLES", tunables, 1);
#else
  (void)argv;
#endif
}

void keepFreedMemory() {
#if defined(__linux__) && defined(__GLIBC__)
  // A threshold set here also stops glibc's own adjustment of it (which follows the sizes
  // freed). Larger blocks (a million-triangle mesh's arrays) are still mapped and returned.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

const char* hugePagesState() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const char* at = tunables ? std::strstr(tunables, kTunable) : nullptr;
  if (!at) return "off";
  return std::strncmp(at + std::strlen(kTunable), "=0", 2) == 0 ? "off" : "on";
}

}  // namespace anisomesh::cli
