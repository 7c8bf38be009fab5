#pragma once
// The adapt command of the CLI (adapt_command.cpp).
namespace anisomesh {

// Runs `anisomesh adapt ...` (argv[1] == "adapt"): exit 0, 2 on a usage error; core
// errors (anisomesh::Error) propagate to main, which reports them with exit 1.
int runAdaptCommand(int argc, char** argv);

}  // namespace anisomesh
