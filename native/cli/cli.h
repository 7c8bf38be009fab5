#pragma once
// Shared pieces of the anisomesh command line: the command table entry, argument walking,
// number parsing and output writing. One command per file (mesh_command.cpp, ...); main.cpp
// lists them in its table.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "anisomesh/io/case_svg.h"
#include "anisomesh/io/run_case.h"

namespace anisomesh::cli {

// A command-line mistake: reported with the usage text, exit code 2.
struct UsageError {
  std::string message;
};

// Walks argv after the command: positionals, flags and options with a value.
class Args {
 public:
  Args(int argc, char** argv) : argc_(argc), argv_(argv) {}
  bool done() const { return i_ >= argc_; }
  std::string next() { return argv_[i_++]; }
  // The value after option (UsageError when there is none).
  const char* value(const std::string& option);

 private:
  int argc_;
  char** argv_;
  int i_ = 2;
};

// One command of the table: its name, its usage lines and what runs it (exit code).
struct Command {
  std::string name;
  std::string usage;
  std::function<int(Args&)> run;
};

// The commands, each defined in its own file.
Command meshCommand();
Command remeshCommand();
Command metricCommand();

// Starts this process again (same arguments) with glibc's malloc on transparent huge pages
// (GLIBC_TUNABLES glibc.malloc.hugetlb=1), unless the tunable is already set or the kernel
// offers none; returns when it does not restart.
void restartWithHugePages(char** argv);
// "on" when the process started with glibc.malloc.hugetlb set (not 0), else "off" (-v prints it).
const char* hugePagesState();
// glibc's malloc keeps what the CLI frees for its next allocations instead of giving it back
// to the kernel: a block under 32 MiB comes from the heap (not a fresh mapping), and the heap
// is trimmed only above 256 MiB free. Each first touch of a fresh page is a fault (~18 us on
// the virtual machine); the stages allocate and free the same sizes again and again.
void keepFreedMemory();

// A nonnegative finite number (UsageError naming option otherwise).
double parseNumber(const std::string& option, const char* text);
// Any finite number.
double parseSignedNumber(const std::string& option, const char* text);
// A positive integer.
long long parseCount(const std::string& option, const char* text);
// The budget options of the meshing commands (--max-elements, --max-control-nodes,
// --max-input-bytes): true when a is one of them, its value parsed and stored.
bool parseBudgetOption(const std::string& a, Args& args, std::int64_t* maxElements, std::int64_t* maxControlNodes);
// "AZ,EL" in degrees, returned in radians.
void parseView(const std::string& option, const std::string& text, CaseSvgOptions& svg);

// UsageError unless out names a writable format (.mesh, .vtk, .obj, .msh, .vtu, .svg).
void requireOutput(const std::string& out);
// True for a .svg path.
bool isSvg(const std::string& path);
// Writes run.mesh to path by extension (.vtu: caseRunVtu, .svg: caseRunSvg with svg).
void writeOutput(const std::string& path, const CaseRun& run, const CaseSvgOptions& svg);
// -v N: a progress callback printing "anisomesh: NN%" lines to stderr when verbosity >= 1.
std::function<bool(double)> progressPrinter(int verbosity);

}  // namespace anisomesh::cli
