// io/atomic_file.h — the one way softmol writes an output file without losing data (issue 15):
// the bytes go to a temporary with a unique name (mkstemp) in the output's own folder, every
// call is checked (write, close), and rename() is the only step that makes the output appear,
// so a reader sees the old file or the whole new one, never a part. The temporary is removed on
// every failure path (the destructor) and on SIGINT/SIGTERM/SIGHUP (a signal handler that
// unlinks the registered temporaries, then re-raises). Errors are io::InputError naming the
// path the user gave, never the temporary.
//
// A symlink as the output is written through, as `cp` does: the file it points to (followed to
// the end of a chain, and created if the link dangles) is replaced and the link stays a link.
// An output that exists and is not a regular file (a device, a FIFO) is refused, as is one that
// is a directory or lies in a folder that does not exist.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <string>

namespace softmol::io {

// A class rather than free functions: its destructor is what removes the temporary when an
// exception leaves a writer half-way.
class TemporaryFile {
 public:
  // Checks the output (not a directory, its folder exists) and creates the temporary beside the
  // file the output resolves to. InputError naming `output` when it cannot.
  explicit TemporaryFile(const std::string& output);
  ~TemporaryFile();  // removes the temporary unless Commit() succeeded
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  // Appends all `size` bytes (retrying short writes and EINTR), or InputError.
  void Write(const void* data, size_t size);
  // Closes the descriptor (checked) so a library can write the file by name (OpenImageIO).
  void CloseForExternalWriter();
  // Closes (checked) and renames the temporary onto the output. InputError on failure, and the
  // temporary is gone either way.
  void Commit();

  const std::string& temporaryPath() const { return temp_; }
  const std::string& outputPath() const { return output_; }

 private:
  [[noreturn]] void Fail(const std::string& what, int err);
  std::string output_;  // as the user gave it (for messages)
  std::string target_;  // where the rename goes (the symlink's final target, or output_)
  std::string temp_;
  int fd_ = -1;
  int slot_ = -1;  // signal-handler registration (-1: none)
  bool committed_ = false;
};

namespace detail {
// Test seam: the write(2) TemporaryFile uses (nullptr restores ::write), so tests can inject
// ENOSPC after N bytes or a signal in the middle of a write.
using WriteFunction = ssize_t (*)(int fd, const void* data, size_t size);
void SetWriteFunctionForTesting(WriteFunction f);
}  // namespace detail

}  // namespace softmol::io
