#include "integration/process_fixture.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "runtime/system_config.h"

namespace stickrep::test {

std::string BinPath(const std::string& name) { return std::string(STICKREP_BINARY_DIR) + "/bin/" + name; }

std::string ConfigPath(const std::string& name) {
  return std::string(STICKREP_SOURCE_DIR) + "/configs/" + name;
}

std::string SourcePath(const std::string& rel) {
  return std::string(STICKREP_SOURCE_DIR) + "/" + rel;
}

double WallNowS() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::pair<int, std::string> Shell(const std::string& command) {
  std::string out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return {-1, ""};
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), pipe)) > 0) out.append(buf, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

std::string WriteTempFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + std::to_string(getpid()) + "_" + name;
  std::ofstream(path) << text;
  return path;
}

DomainLock::DomainLock(int domain_id) {
  const std::string path =
      ::testing::TempDir() + "/stickrep_domain_" + std::to_string(domain_id) + ".lock";
  // Close-on-exec: the processes a test starts must not inherit the lock, or one left behind
  // by a killed test would hold the domain for ever.
  fd_ = open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0666);
  if (fd_ >= 0) flock(fd_, LOCK_EX);
}

DomainLock::~DomainLock() {
  if (fd_ >= 0) close(fd_);
}

ProcessFixture::ProcessFixture(int domain_id) : domain_id_(domain_id), lock_(domain_id) {
  participant_ = std::make_unique<runtime::Participant>(
      runtime::ParticipantConfig{domain_id, "stickrep-test", "", "", {}},
      runtime::QosCatalog::LoadFile(ConfigPath("qos.yaml")));
}

ProcessFixture::~ProcessFixture() {
  for (auto& p : processes_) {
    if (!p->Exited()) {
      p->Signal(SIGKILL);
      p->WaitExit(5.0);
    }
  }
}

launch::ChildProcess& ProcessFixture::Start(const std::string& executable,
                                            const std::vector<std::string>& args) {
  std::vector<std::string> argv{BinPath(executable), "--domain", std::to_string(domain_id_)};
  argv.insert(argv.end(), args.begin(), args.end());
  processes_.push_back(std::make_unique<launch::ChildProcess>(executable, argv));
  return *processes_.back();
}

bool ProcessFixture::SpinUntil(const std::function<bool()>& done, double timeout_s) {
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(timeout_s));
  while (!done()) {
    if (std::chrono::steady_clock::now() > until) return false;
    executor_.SpinOnce(std::chrono::milliseconds(20));
    for (auto& p : processes_) p->ReadLines();
  }
  return true;
}

void ProcessFixture::StopAllAndExpectCleanExit(double timeout_s) {
  std::vector<launch::ChildProcess*> running;
  for (auto& p : processes_) {
    if (!p->Exited()) running.push_back(p.get());  // ones a test ended itself are its business
  }
  for (auto* p : running) p->Signal(SIGTERM);
  for (auto* p : running) {
    ASSERT_TRUE(p->WaitExit(timeout_s)) << p->name() << " did not stop\n" << Outputs();
    EXPECT_EQ(p->exit_code(), 0) << p->name() << " (signal " << p->term_signal() << ")\n"
                                 << p->output();
  }
}

std::string ConfigWith(const std::string& file, const std::map<std::string, std::string>& keys) {
  std::ifstream in(ConfigPath(file));
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    for (const auto& [key, value] : keys) {
      if (line.rfind("  " + key + ":", 0) == 0) line = "  " + key + ": " + value;
    }
    out << line << "\n";
  }
  return out.str();
}

std::string SmallMapSystem(const std::string& name) {
  return WriteTempFile(name, ConfigWith("system.yaml", {{"qos_file", ConfigPath("qos.yaml")},
                                                        {"robot_file", ConfigPath("robot.yaml")},
                                                        {"map_file", kSmallMap}}));
}

std::string ProcessFixture::Outputs() {
  std::ostringstream out;
  for (auto& p : processes_) {
    p->ReadLines(true);
    out << "---- " << p->name() << "\n" << p->output();
  }
  return out.str();
}

}  // namespace stickrep::test
