// tests/cli/run_command.h — runs the softmol binary as a user would and captures its exit
// status, stdout and stderr (for the end-to-end CLI tests).
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace softmol::test {

struct CommandResult {
  int exitCode = -1;
  std::string out, err;
};

inline std::string Slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `SOFTMOL_EXE args` through the shell (args are already quoted by the caller).
inline CommandResult RunSoftmol(const std::string& args, const std::filesystem::path& scratch) {
  const auto out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  const std::string cmd = std::string("'") + SOFTMOL_EXE + "' " + args + " >'" + out.string() +
                          "' 2>'" + err.string() + "' </dev/null";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = Slurp(out);
  r.err = Slurp(err);
  return r;
}

// A fresh, empty folder under the system temp dir for one test.
inline std::filesystem::path ScratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("softmol_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string Data(const std::string& file) { return std::string(SOFTMOL_DATA_DIR) + "/" + file; }

// In single quotes for the shell (appended piece by piece: GCC 12 misreports "'" + std::string,
// -Wrestrict).
inline std::string Q(const std::filesystem::path& p) {
  std::string s = "'";
  s += p.string();
  s += "'";
  return s;
}

// Runs a shell command (a pipeline or list is fine) with its output into `log`; the exit status.
inline int Shell(const std::string& cmd, const std::filesystem::path& log) {
  const int status = std::system(("(" + cmd + ") >" + Q(log) + " 2>&1 </dev/null").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace softmol::test
