// tests/cli/cli_slurm_test.cpp — the README's Slurm job array on a one-node cluster this test
// starts on localhost (Debian's slurmctld and slurmd, a minimal slurm.conf in a scratch folder,
// auth/none so no munge key is needed, ports the kernel picks): 3 array tasks render 3 shards
// of md.xtc, and their files are exactly the single run's, byte for byte. Skipped, saying why,
// where Slurm is not installed or its daemons cannot start.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include <gtest/gtest.h>

#include "tests/cli/run_command.h"

namespace softmol::test {
namespace {

bool OnPath(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

// A TCP port nobody listens on now (the kernel's pick for port 0).
int FreePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof(addr);
  int port = 0;
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0 &&
      getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0)
    port = ntohs(addr.sin_port);
  close(fd);
  return port;
}

std::string ShortHostName() {
  char name[256] = {};
  gethostname(name, sizeof(name) - 1);
  std::string h(name);
  return h.substr(0, h.find('.'));
}

std::string UserName() {
  const char* u = std::getenv("USER");
  return getuid() == 0 ? "root" : (u ? u : "root");
}

// A daemon in the foreground, as a child process ended by the destructor.
class Daemon {
 public:
  Daemon(const std::string& command, const std::filesystem::path& log) {
    pid_ = fork();
    if (pid_ == 0) {
      const std::string line = "exec " + command + " >" + Q(log.string()) + " 2>&1 </dev/null";
      execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  ~Daemon() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    int status = 0;
    for (int i = 0; i < 100 && waitpid(pid_, &status, WNOHANG) == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (waitpid(pid_, &status, WNOHANG) == 0) kill(pid_, SIGKILL), waitpid(pid_, &status, 0);
  }
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

 private:
  pid_t pid_ = -1;
};

void WriteSlurmConf(const std::filesystem::path& dir, const std::string& host) {
  std::filesystem::create_directories(dir / "state");
  std::filesystem::create_directories(dir / "spool");
  const std::string d = dir.string();
  std::ofstream(dir / "slurm.conf") << "ClusterName=softmoltest\n"
                                    << "SlurmctldHost=" << host << "(127.0.0.1)\n"
                                    << "AuthType=auth/none\nCredType=cred/none\n"
                                    << "SlurmUser=" << UserName() << "\nSlurmdUser=" << UserName() << "\n"
                                    << "SlurmctldPort=" << FreePort() << "\nSlurmdPort=" << FreePort() << "\n"
                                    << "StateSaveLocation=" << d << "/state\nSlurmdSpoolDir=" << d << "/spool\n"
                                    << "SlurmctldPidFile=" << d << "/slurmctld.pid\nSlurmdPidFile=" << d << "/slurmd.pid\n"
                                    << "SlurmctldLogFile=" << d << "/slurmctld.log\nSlurmdLogFile=" << d << "/slurmd.log\n"
                                    << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
                                    << "SelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n"
                                    << "ReturnToService=2\nMpiDefault=none\n"
                                    << "AccountingStorageType=accounting_storage/none\nJobAcctGatherType=jobacct_gather/none\n"
                                    << "NodeName=" << host << " NodeAddr=127.0.0.1 CPUs=1 State=UNKNOWN\n"
                                    << "PartitionName=test Nodes=" << host << " Default=YES MaxTime=INFINITE State=UP\n";
}

// Waits (up to 30 s) until the node reports idle.
bool NodeIdle(const std::filesystem::path& dir) {
  const std::string cmd = "sinfo -h -o %t >" + Q((dir / "sinfo.txt").string()) + " 2>&1";
  for (int i = 0; i < 60; ++i) {
    if (std::system(cmd.c_str()) == 0 && Slurp(dir / "sinfo.txt").find("idle") != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  return false;
}

std::map<std::string, std::string> Pngs(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".png") files[e.path().filename().string()] = Slurp(e.path());
  return files;
}

TEST(CliSlurm, JobArrayShardsReassembleIntoTheSingleRun) {
  for (const char* program : {"slurmctld", "slurmd", "sbatch", "sinfo"})
    if (!OnPath(program) && !OnPath(std::string("/usr/sbin/") + program))
      GTEST_SKIP() << program << " is not installed (Debian: apt-get install slurmctld slurmd slurm-client)";
  const auto dir = ScratchDir("slurm");
  const std::string host = ShortHostName();
  WriteSlurmConf(dir / "cluster", host);
  setenv("SLURM_CONF", (dir / "cluster/slurm.conf").string().c_str(), 1);
  const std::string sbin = OnPath("slurmctld") ? "" : "/usr/sbin/";
  Daemon controller(sbin + "slurmctld -D -i", dir / "cluster/slurmctld.out");
  Daemon node(sbin + "slurmd -D -N " + host, dir / "cluster/slurmd.out");
  if (!NodeIdle(dir))
    GTEST_SKIP() << "the Slurm daemons did not start here (sinfo: " << Slurp(dir / "sinfo.txt")
                 << "); see " << (dir / "cluster").string() << "/slurmctld.out and slurmd.out";

  const std::string md = Q(Data("md.pdb")) + " --trajectory " + Q(Data("md.xtc")) + " --frames 0:20:5 --size 64x48 -q";
  std::filesystem::create_directories(dir / "whole");
  std::filesystem::create_directories(dir / "frames");
  const CommandResult whole = RunSoftmol("render " + md + " -o " + Q((dir / "whole/md_%05d.png").string()), dir);
  ASSERT_EQ(whole.exitCode, 0) << whole.err;
  // The README's job array, three tasks.
  std::ofstream(dir / "render.sh") << "#!/bin/bash\n#SBATCH --array=0-2\n#SBATCH --output=" << (dir / "task_%a.out").string()
                                   << "\n'" << SOFTMOL_EXE << "' render " << md << " -o "
                                   << Q((dir / "frames/md_%05d.png").string())
                                   << " --threads 1 --shard \"$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT\"\n";
  const std::string submit = "timeout 300 sbatch --wait " + Q((dir / "render.sh").string()) + " >" +
                             Q((dir / "sbatch.txt").string()) + " 2>&1";
  ASSERT_EQ(std::system(submit.c_str()), 0) << Slurp(dir / "sbatch.txt") << Slurp(dir / "task_0.out");
  const std::map<std::string, std::string> expected = Pngs(dir / "whole"), got = Pngs(dir / "frames");
  EXPECT_EQ(expected.size(), 5u);
  EXPECT_TRUE(got == expected) << got.size() << " files from the job array, " << expected.size() << " from one run";
}

}  // namespace
}  // namespace softmol::test
