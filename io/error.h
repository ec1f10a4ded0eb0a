// io/error.h — softmol's errors and exit codes. InputError is bad input (a file, record,
// option or scene key): readers throw it with the exact place. InternalError is a failure that
// is not the input's fault (a dependency or driver that fails, a bug). cli/main.cpp is the one
// boundary: it catches everything, prints one line and exits with one of the codes below.
// Kernels and passes never throw; broken invariants are SOFTMOL_CHECK (common/check.h).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace softmol::io {

// Where the problem is. line/column 0 = unknown; `detail` names a frame or record when a line
// does not apply ("frame 17"); file may be an option name ("--size").
struct SourceLocation {
  SourceLocation() = default;
  // Implicit, so `InputError({path}, ...)` and `InputError({path, line}, ...)` read naturally.
  SourceLocation(std::string file_, long line_ = 0, int column_ = 0, std::string detail_ = {})
      : file(std::move(file_)), line(line_), column(column_), detail(std::move(detail_)) {}

  std::string file;
  long line = 0;
  int column = 0;
  std::string detail;
  std::string ToString() const;  // "1abc.pdb:1204:31", "md.xtc: frame 17", "--size"
};

// Exit codes of the softmol command (listed in `softmol --help`).
enum ExitCode : int {
  kExitOk = 0,
  kExitDifferent = 1,    // `softmol diff`: the images differ (as cmp)
  kExitBadInput = 2,     // InputError, or a command line CLI11 rejects
  kExitInternal = 3,     // InternalError, or any other exception from a dependency
  kExitOutOfMemory = 4,  // std::bad_alloc
};

class InputError : public std::runtime_error {
 public:
  // what() is "<where>: <message>", e.g. "1abc.pdb:1204:31: x coordinate is not a number: 'l2.500'"
  InputError(SourceLocation where, std::string_view message);
  const SourceLocation& where() const noexcept { return where_; }
  const std::string& message() const noexcept { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

// Not the input's fault: a dependency or driver that fails, or a broken assumption. what() is
// "internal error: <message>".
class InternalError : public std::runtime_error {
 public:
  explicit InternalError(std::string_view message)
      : std::runtime_error("internal error: " + std::string(message)) {}
};

}  // namespace softmol::io
