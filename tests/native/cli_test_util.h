#pragma once
// Running the native CLI from tests: per-test temporary files, captured exit code,
// stdout and stderr.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace clitest {

struct CliRun {
  int code;
  std::string out, err;
};

// A temporary path unique to the running test (ctest runs tests in parallel processes).
// Parametrized tests' names hold '/', which must not become directories.
inline std::string tmp(const std::string& name) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string id = std::string(info->test_suite_name()) + "_" + info->name();
  for (char& c : id)
    if (c == '/') c = '_';
  return ::testing::TempDir() + "anisomesh_" + id + "_" + name;
}

// Path of an example case.
inline std::string example(const std::string& name) { return std::string(ANISOMESH_SOURCE_DIR) + "/examples/" + name; }

// Whole file as text ("" when missing).
inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void writeFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

inline bool exists(const std::string& path) { return std::ifstream(path).good(); }

// Runs the CLI with the given arguments, capturing exit code, stdout and stderr; `env`
// goes in front of the command (e.g. "env -u NAME" or "NAME=value").
inline CliRun run(const std::string& args, const std::string& env = "") {
  const std::string out = tmp("stdout.txt"), err = tmp("stderr.txt");
  const std::string cmd = env + " \"" + ANISOMESH_CLI_PATH + "\" " + args + " >\"" + out + "\" 2>\"" + err + "\"";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

}  // namespace clitest
