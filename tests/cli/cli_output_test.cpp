// tests/cli/cli_output_test.cpp — the command never loses data silently (issue 15): a full disk
// (a real 16 KiB tmpfs when this process may mount one, skipped with a message otherwise) exits
// non-zero with nothing under the output name and no temporary; two renders to one name leave
// one whole image; SIGTERM while writing leaves no temporary; a directory or a missing folder
// as the output gets a message saying so.
#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

#include <gtest/gtest.h>

#include "io/image_io.h"
#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

namespace fs = std::filesystem;
const std::string kPept = "'" + Data("pept.pdb") + "'";
const std::string k1tii = "'" + Data("1tii.pdb") + "'";

// Files in `dir` other than the captured stdout/stderr.
std::vector<std::string> Outputs(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n != "stdout.txt" && n != "stderr.txt") names.push_back(n);
  }
  return names;
}

TEST(CliOutput, DirectoryAsOutputIsNamed) {
  const auto dir = ScratchDir("out_directory");
  fs::create_directory(dir / "out.png");
  const CommandResult r = RunSoftmol("render --ao none " + kPept + " --size 32x24 -o '" + (dir / "out.png").string() + "'", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("out.png: the output is a directory"), std::string::npos) << r.err;
}

TEST(CliOutput, MissingFolderIsNamed) {
  const auto dir = ScratchDir("out_missing");
  const std::string folder = (dir / "no" / "such").string();
  const CommandResult r = RunSoftmol("render --ao none " + kPept + " --size 32x24 -o '" + folder + "/out.png'", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("the output folder '" + folder + "' does not exist"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("Success"), std::string::npos) << r.err;
}

// A sequence writes frame N while N+1 renders: a frame that cannot be written still stops the
// run with its own name in the message, the frames before it stay whole, none after it is
// written, and no temporary is left.
TEST(CliOutput, SequenceFrameThatCannotBeWrittenStopsTheRun) {
  const auto dir = ScratchDir("out_sequence");
  fs::create_directory(dir / "tt_00001.png");
  const CommandResult r =
      RunSoftmol("render --ao none " + kPept + " --size 64x48 --turntable 4 -o '" + (dir / "tt_%05d.png").string() + "'", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("tt_00001.png: the output is a directory"), std::string::npos) << r.err;
  std::vector<std::string> left = Outputs(dir);
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"tt_00000.png", "tt_00001.png"}));
  EXPECT_EQ(io::ReadImage8((dir / "tt_00000.png").string()).width, 64);
}

// A tmpfs of 16 KiB mounted on `dir` for the test's lifetime (needs CAP_SYS_ADMIN).
struct SmallDisk {
  fs::path dir;
  bool mounted = false;
  explicit SmallDisk(fs::path d) : dir(std::move(d)) {
    fs::create_directories(dir);
    mounted = mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=16k") == 0;
  }
  ~SmallDisk() {
    if (mounted) umount2(dir.c_str(), MNT_DETACH);
  }
};

TEST(CliOutput, FullDiskExitsNonZeroAndLeavesNothing) {
  const auto scratch = ScratchDir("out_full_disk");
  SmallDisk disk(scratch / "disk");
  if (!disk.mounted) GTEST_SKIP() << "cannot mount a tmpfs here (not root?): " << std::strerror(errno);
  for (const std::string name : {"full.png", "full.exr"}) {
    const std::string out = (disk.dir / name).string();
    const CommandResult r = RunSoftmol("render --ao none " + k1tii + " --size 400x300 -o '" + out + "'", scratch);
    EXPECT_EQ(r.exitCode, 2) << name << ": " << r.err;
    EXPECT_NE(r.err.find(out), std::string::npos) << r.err;
    // zlib's PNG path reports errno; OpenEXR words it its own way.
    if (name == "full.png") {
      EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    }
    EXPECT_TRUE(Outputs(disk.dir).empty()) << name << " left " << Outputs(disk.dir).front();
  }
}

TEST(CliOutput, ConcurrentRendersToOneNameLeaveOneWholeImage) {
  const auto dir = ScratchDir("out_concurrent");
  const std::string out = (dir / "same.png").string();
  const std::string exe = std::string("'") + SOFTMOL_EXE + "'";
  std::string cmd;
  for (int k = 0; k < 2; ++k) {
    const std::string size = k == 0 ? "320x240" : "256x192";
    cmd += "(" + exe + " render --ao none " + kPept + " --size " + size + " -o '" + out + "' 2>'" + (dir / ("err" + std::to_string(k))).string() +
           "'; echo $? >'" + (dir / ("rc" + std::to_string(k))).string() + "') & ";
  }
  ASSERT_EQ(std::system((cmd + "wait").c_str()), 0);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(Slurp(dir / ("rc" + std::to_string(k))), "0\n") << Slurp(dir / ("err" + std::to_string(k)));
    fs::remove(dir / ("rc" + std::to_string(k)));
    fs::remove(dir / ("err" + std::to_string(k)));
  }
  EXPECT_EQ(Outputs(dir), std::vector<std::string>{"same.png"});
  const io::Image8 img = io::ReadImage8(out);
  EXPECT_TRUE((img.width == 320 && img.height == 240) || (img.width == 256 && img.height == 192));
}

// SIGTERM as soon as the temporary appears: afterwards there is no temporary, and either the
// output is absent (killed in time) or whole (the write won the race).
// Large enough that the PNG write lasts long enough to be seen; under ASan at -O0 everything is
// ~10× slower, so a quarter of the pixels lasts as long and saves a minute of CI.
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* kSigtermSize = "3000x2000";
#else
constexpr const char* kSigtermSize = "6000x4000";
#endif

TEST(CliOutput, SigtermWhileWritingLeavesNoTemporary) {
  const auto dir = ScratchDir("out_sigterm");
  const std::string out = (dir / "big.png").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (freopen("/dev/null", "w", stderr) == nullptr) _exit(126);
    execl(SOFTMOL_EXE, SOFTMOL_EXE, "render", Data("pept.pdb").c_str(), "--size", kSigtermSize, "--ao", "none", "-o", out.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  bool sawTemporary = false;
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!sawTemporary && waitpid(pid, &status, WNOHANG) == 0 && std::chrono::steady_clock::now() < deadline) {
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename().string().rfind(".big.png.", 0) == 0) sawTemporary = true;
    if (sawTemporary) kill(pid, SIGTERM);
    else std::this_thread::sleep_for(std::chrono::microseconds(300));
  }
  if (sawTemporary) waitpid(pid, &status, 0);
  EXPECT_TRUE(Outputs(dir).empty() || Outputs(dir) == std::vector<std::string>{"big.png"})
      << "left " << Outputs(dir).front();
  if (fs::exists(out)) {
    EXPECT_EQ(io::ReadImage8(out).width, std::atoi(kSigtermSize));
  }
  if (!sawTemporary) GTEST_SKIP() << "the render finished before its temporary was seen";
  EXPECT_TRUE(WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) == 0));
}

}  // namespace
}  // namespace softmol::test
