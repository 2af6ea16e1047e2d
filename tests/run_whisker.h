// Test helper: runs the whisker binary under test (WHISKER_BIN) with a
// command line and returns its exit code and its stdout and stderr together.
#pragma once

#include <cstdio>
#include <string>

#include <sys/wait.h>

namespace whisker {

struct Result {
  int code;
  std::string output;  // stdout and stderr
};

inline Result run(const std::string& args) {
  const std::string cmd = std::string(WHISKER_BIN) + " " + args + " 2>&1";
  Result r{-1, {}};
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p)) r.output += buf;
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace whisker
