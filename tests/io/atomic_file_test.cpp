// tests/io/atomic_file_test.cpp — no silent data loss (issue 15): a failed write (ENOSPC
// injected after N bytes) throws a message naming the output and leaves nothing under either
// name; concurrent writers to one name leave one whole file; a signal in the middle of a write
// leaves no temporary; directories, missing folders and symlinks get the documented behaviour.
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "io/error.h"
#include "io/image_io.h"

namespace softmol::io {
namespace {

namespace fs = std::filesystem;

fs::path Scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("softmol_atomic_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::vector<std::string> Entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

std::vector<uint8_t> Noise(int w, int h, int c, uint32_t seed) {
  std::vector<uint8_t> px(size_t(w) * size_t(h) * size_t(c));
  for (auto& p : px) p = uint8_t((seed = seed * 1664525u + 1013904223u) >> 24);
  return px;
}

// The fault: the disk fills after kRoom bytes.
constexpr size_t kRoom = 4096;
std::atomic<size_t> g_written{0};
ssize_t FullDisk(int fd, const void* data, size_t size) {
  const size_t used = g_written.load();
  if (used >= kRoom) {
    errno = ENOSPC;
    return -1;
  }
  const size_t n = std::min(size, kRoom - used);
  g_written += n;
  return ::write(fd, data, n);
}

struct FaultScope {
  explicit FaultScope(detail::WriteFunction f) { g_written = 0, detail::SetWriteFunctionForTesting(f); }
  ~FaultScope() { detail::SetWriteFunctionForTesting(nullptr); }
};

TEST(AtomicFile, DiskFullLeavesNothingAndNamesTheOutput) {
  const fs::path dir = Scratch("enospc");
  const std::string out = (dir / "full.png").string();
  FaultScope fault(FullDisk);
  try {
    WritePng(out, 200, 200, 3, Noise(200, 200, 3, 1));
    FAIL() << "the write succeeded on a full disk";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(out), std::string::npos) << what;
    EXPECT_NE(what.find("No space left on device"), std::string::npos) << what;
    EXPECT_EQ(what.find(".full.png."), std::string::npos) << "names the temporary: " << what;
  }
  EXPECT_TRUE(Entries(dir).empty()) << "left " << Entries(dir).front();
}

TEST(AtomicFile, DiskFullKeepsTheOldFile) {
  const fs::path dir = Scratch("enospc_old");
  const std::string out = (dir / "keep.png").string();
  const std::vector<uint8_t> old = Noise(8, 8, 3, 5);
  WritePng(out, 8, 8, 3, old);
  {
    FaultScope fault(FullDisk);
    EXPECT_THROW(WritePng(out, 300, 300, 3, Noise(300, 300, 3, 2)), InputError);
  }
  EXPECT_EQ(Entries(dir), std::vector<std::string>{"keep.png"});
  EXPECT_EQ(ReadImage8(out).pixels, old);
}

TEST(AtomicFile, ConcurrentWritersLeaveOneWholeFile) {
  const fs::path dir = Scratch("concurrent");
  const std::string out = (dir / "same.png").string();
  std::vector<std::vector<uint8_t>> images;
  for (int k = 0; k < 4; ++k) images.push_back(Noise(120, 90, 4, uint32_t(k + 10)));
  std::vector<std::thread> writers;
  for (int k = 0; k < 4; ++k)
    writers.emplace_back([&, k] {
      for (int i = 0; i < 10; ++i) WritePng(out, 120, 90, 4, images[size_t(k)]);
    });
  for (auto& t : writers) t.join();
  EXPECT_EQ(Entries(dir), std::vector<std::string>{"same.png"});
  const Image8 got = ReadImage8(out);
  bool matchesOne = false;
  for (const auto& im : images) matchesOne = matchesOne || got.pixels == im;
  EXPECT_TRUE(matchesOne) << "the file is not one writer's whole image";
}

// SIGTERM arrives in the middle of the write: the handler removes the temporary and the process
// dies of the signal, as it would without softmol's handler.
ssize_t TerminateMidway(int fd, const void* data, size_t size) {
  const ssize_t n = ::write(fd, data, std::min<size_t>(size, 100));
  raise(SIGTERM);
  return n;
}

TEST(AtomicFile, SigtermMidWriteLeavesNoTemporary) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path dir = Scratch("sigterm");
  const std::string out = (dir / "killed.png").string();
  EXPECT_EXIT(
      {
        detail::SetWriteFunctionForTesting(TerminateMidway);
        WritePng(out, 64, 64, 3, Noise(64, 64, 3, 3));
      },
      testing::KilledBySignal(SIGTERM), "");
  EXPECT_TRUE(Entries(dir).empty()) << "left " << Entries(dir).front();
}

TEST(AtomicFile, DirectoryAsOutputIsRefused) {
  const fs::path dir = Scratch("directory");
  fs::create_directory(dir / "sub.png");
  try {
    WritePng((dir / "sub.png").string(), 4, 4, 3, Noise(4, 4, 3, 4));
    FAIL() << "wrote over a directory";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(Entries(dir), std::vector<std::string>{"sub.png"});
}

TEST(AtomicFile, FifoIsNotReplaced) {
  const fs::path dir = Scratch("fifo");
  ASSERT_EQ(mkfifo((dir / "pipe.png").c_str(), 0600), 0);
  EXPECT_THROW(WritePng((dir / "pipe.png").string(), 4, 4, 3, Noise(4, 4, 3, 4)), InputError);
  EXPECT_TRUE(fs::is_fifo(dir / "pipe.png"));
  EXPECT_EQ(Entries(dir), std::vector<std::string>{"pipe.png"});
}

TEST(AtomicFile, NewFileGetsTheUmaskMode) {
  const fs::path dir = Scratch("newmode");
  const mode_t mask = umask(022);
  WritePng((dir / "n.png").string(), 4, 4, 3, Noise(4, 4, 3, 1));
  umask(mask);
  EXPECT_EQ(fs::status(dir / "n.png").permissions() & fs::perms::mask, fs::perms(0644));
}

TEST(AtomicFile, MissingFolderIsNamed) {
  const fs::path dir = Scratch("missing");
  const std::string folder = (dir / "not" / "there").string();
  try {
    WritePng(folder + "/x.png", 4, 4, 3, Noise(4, 4, 3, 4));
    FAIL() << "wrote into a missing folder";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'" + folder + "' does not exist"), std::string::npos) << what;
  }
}

TEST(AtomicFile, SymlinkIsWrittenThrough) {
  const fs::path dir = Scratch("symlink");
  fs::create_directory(dir / "real");
  const std::string target = (dir / "real" / "image.png").string();
  WritePng(target, 4, 4, 3, Noise(4, 4, 3, 1));
  fs::create_symlink("real/image.png", dir / "link.png");  // relative, as ln -s makes them
  const std::vector<uint8_t> fresh = Noise(6, 5, 3, 9);
  WritePng((dir / "link.png").string(), 6, 5, 3, fresh);
  EXPECT_TRUE(fs::is_symlink(dir / "link.png")) << "the link was replaced";
  EXPECT_EQ(ReadImage8(target).pixels, fresh) << "the link's target was not rewritten";
  EXPECT_EQ(Entries(dir / "real"), std::vector<std::string>{"image.png"});

  fs::create_symlink("real/new.png", dir / "dangling.png");  // a dangling link creates its target
  WritePng((dir / "dangling.png").string(), 6, 5, 3, fresh);
  EXPECT_EQ(ReadImage8((dir / "real" / "new.png").string()).pixels, fresh);
}

TEST(AtomicFile, ReplacedFileKeepsItsMode) {
  const fs::path dir = Scratch("mode");
  const std::string out = (dir / "m.png").string();
  WritePng(out, 4, 4, 3, Noise(4, 4, 3, 1));
  fs::permissions(out, fs::perms(0640));
  WritePng(out, 4, 4, 3, Noise(4, 4, 3, 2));
  EXPECT_EQ(fs::status(out).permissions() & fs::perms::mask, fs::perms(0640));
}

}  // namespace
}  // namespace softmol::io
