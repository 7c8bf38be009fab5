// anisomesh command-line interface (native). Each command lives in its own file and is
// listed in commands() below; this file dispatches and reports errors.
#include <iostream>
#include <string>
#include <vector>

#include "adapt_command.h"
#include "anisomesh/core/error.h"
#include "anisomesh/core/version.h"
#include "cli.h"

namespace {

using namespace anisomesh::cli;

// The command table: add a command by adding its file and one line here.
const std::vector<Command>& commands() {
  static const std::vector<Command> table = {meshCommand(), remeshCommand(), metricCommand()};
  return table;
}

int usage(std::ostream& os, int code) {
  os << "usage: anisomesh <command> [options]\ncommands:\n";
  for (const Command& c : commands()) os << c.usage;
  os << "  adapt IN.mesh -sol F.sol|-field EXPR -o OUT (-err E|-nv N) ...\n"
        "                            adapt IN.mesh to a solution (anisomesh adapt --help for the options)\n"
        "  --version                 print the version\n"
        "--max-control-nodes: control-space node budget (default: max-elements / 64 + 262144);\n"
        "--max-input-bytes: larger input files are refused (default 536870912).\n"
        "--stats prints one JSON object on stdout. Errors: exit 1 (bad input), 2 (bad usage).\n";
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage(std::cerr, 2);
  restartWithHugePages(argv);
  keepFreedMemory();
  const std::string cmd = argv[1];
  try {
    if (cmd == "--version") {
      std::cout << "anisomesh " << anisomesh::version() << "\n";
      return 0;
    }
    if (cmd == "--help" || cmd == "-h") return usage(std::cout, 0);
    for (const Command& c : commands()) {
      if (c.name != cmd) continue;
      Args args(argc, argv);
      return c.run(args);
    }
    if (cmd == "adapt") return anisomesh::runAdaptCommand(argc, argv);
    std::cerr << "anisomesh: unknown command '" << cmd << "'\n";
    return usage(std::cerr, 2);
  } catch (const UsageError& e) {
    std::cerr << "anisomesh: usage error: " << e.message << "\n";
    return usage(std::cerr, 2);
  } catch (const anisomesh::Error& e) {
    std::cerr << "anisomesh: error " << anisomesh::errorCodeName(e.code()) << ": " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "anisomesh: error OUT_OF_MEMORY: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "anisomesh: error INTERNAL: " << e.what() << "\n";
    return 1;
  }
}
