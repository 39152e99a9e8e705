#pragma once
// Runs the real `ibfvs` executable in a temporary folder, as a user would.

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "helpers.h"

namespace ibfvs::test {

struct Result {
  int status = -1;
  std::string out, err;
};

class CommandTest : public ::testing::Test {
 protected:
  // Runs `ibfvs ARGS` in the temp folder with a time limit, so a hang fails
  // instead of blocking the suite. `env` is prefixed to the command.
  Result run(const std::string& args, const std::string& env = "") {
    const std::string cmd = "cd '" + dir_.path().string() + "' && " + env + " timeout 120 '" +
                            IBFVS_EXE + "' " + args + " >stdout.txt 2>stderr.txt </dev/null";
    const int raw = std::system(cmd.c_str());
    Result r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    r.out = test::read_file(dir_ / "stdout.txt");
    r.err = test::read_file(dir_ / "stderr.txt");
    return r;
  }
  // Expects a clean failure: exit 1 (not a crash, not the timeout), one line
  // on stderr that starts with "ibfvs: error:" and contains `needle`.
  void expect_error(const std::string& args, const std::string& needle) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ibfvs: error: ", 0), 0u) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << args << ": expected '" << needle << "' in\n"
                                                     << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
  }
  std::string file(const std::string& name, const std::string& text) {
    return test::write_file(dir_ / name, text).string();
  }
  test::TempDir dir_;
};

}  // namespace ibfvs::test
