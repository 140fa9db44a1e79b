#pragma once
// Runs the built experiment executables from tests (mains_test.cpp, tune_mains_test.cpp):
// stdout and stderr captured, the exit code returned.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "test_paths.h"

namespace shadowlab::test {

struct ProcResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs build/programs/<cmd> (program and arguments) with `env` ("NAME=value …", may be
// empty) in front, capturing stdout and stderr.
inline ProcResult run_env(const std::string& env, const std::string& cmd) {
  // One stderr file per process: CTest runs the tests of this file in parallel processes.
  const std::string err_path = test::binary_path("mains_stderr_" + std::to_string(getpid()) + ".txt");
  const std::string full = env + (env.empty() ? "" : " ") + std::string(SHADOWLAB_BINARY_DIR) +
                           "/programs/" + cmd + " 2>" + err_path;
  ProcResult r;
  FILE* p = popen(full.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream f(err_path);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  return r;
}

inline ProcResult run(const std::string& cmd) { return run_env("", cmd); }

// Expects exit code 2 and one line on stderr containing needle.
inline void expect_clear_error(const std::string& cmd, const std::string& needle) {
  const ProcResult r = run(cmd);
  EXPECT_EQ(r.exit_code, 2) << cmd << "\nstderr: " << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << cmd << "\nstderr: " << r.err;
  // One line: exactly one newline, at the end.
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << cmd << "\nstderr: " << r.err;
}


// A JSON file the programs wrote.
inline nlohmann::json read_json(const std::string& path) {
  std::ifstream f(path);
  return nlohmann::json::parse(f);
}

}  // namespace shadowlab::test
