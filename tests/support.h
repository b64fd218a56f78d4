// What many test files need: reading a file whole, writing one, quoting a shell word, the exit
// code of a std::system call, the captured outcome of a run of the binary, the shared folder
// beside the repository, and a skip that CTest reports as skipped.
#pragma once
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace offsetopt::test {

// The file's bytes; empty when it cannot be read (a test then fails on what it expected).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline void write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// One word for sh, single-quoted (a quote inside becomes '\'').
inline std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The exit code std::system's `status` stands for: 128 + N when killed by signal N (as sh says;
// `timeout` itself exits 124), -1 when no shell could be started.
inline int exit_code_of(int status) {
  if (status == -1) return -1;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

// A run of the offsetopt binary: its exit code (exit_code_of) and what it printed.
struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

// The shared folder beside the repository (real meshes, posed meshes, independent tools):
// $OFFSETOPT_SHARED_DIR when set (a test run can point it elsewhere, or at nothing), else
// ../shared from the source tree. Tests must pass without it, reporting a skip (skip_test).
inline std::filesystem::path shared_dir() {
  const char* set = std::getenv("OFFSETOPT_SHARED_DIR");
  return set ? std::filesystem::path(set) : std::filesystem::path(OFFSETOPT_SOURCE_DIR) / ".." / "shared";
}

// Says that the running test case is skipped and why, in a line CTest reads
// (tests/CMakeLists.txt SKIP_REGULAR_EXPRESSION) to report the test as skipped rather than
// passed. The caller returns right after; doctest 2.4 has no skip once a case has started.
inline void skip_test(const std::string& why) {
  const std::string line = "skipped: " + why;
  MESSAGE(line);
  std::cout << "OFFSETOPT_TEST_SKIPPED: " << why << std::endl;
}

}  // namespace offsetopt::test
