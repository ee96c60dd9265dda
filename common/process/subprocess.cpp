#include "common/process/subprocess.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace fleetmap::process {
namespace {

std::vector<std::string> MergedEnvironment(const std::map<std::string, std::string>& extra) {
  std::map<std::string, std::string> merged;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    const std::string text(*entry);
    const size_t equals = text.find('=');
    if (equals != std::string::npos) merged[text.substr(0, equals)] = text.substr(equals + 1);
  }
  for (const auto& [key, value] : extra) merged[key] = value;
  std::vector<std::string> out;
  for (const auto& [key, value] : merged) out.push_back(key + "=" + value);
  return out;
}

// A new empty temporary file; returns its descriptor and sets `path`.
int TemporaryFile(std::string* path) {
  char path_template[] = "/tmp/fleetmap-process-output-XXXXXX";
  const int fd = mkstemp(path_template);
  if (fd < 0) throw std::runtime_error("mkstemp failed");
  *path = path_template;
  return fd;
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::vector<char*> CStrings(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (std::string& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

}  // namespace

Subprocess::Subprocess(std::vector<std::string> argv, std::map<std::string, std::string> env) {
  const int out_fd = TemporaryFile(&stdout_path_);
  const int err_fd = TemporaryFile(&stderr_path_);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err_fd, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);

  std::vector<std::string> env_strings = MergedEnvironment(env);
  std::vector<char*> c_argv = CStrings(argv);
  std::vector<char*> c_env = CStrings(env_strings);
  if (posix_spawn(&pid_, c_argv[0], &actions, nullptr, c_argv.data(), c_env.data()) != 0) {
    pid_ = -1;
  }
  posix_spawn_file_actions_destroy(&actions);
  close(out_fd);
  close(err_fd);
}

Subprocess::~Subprocess() {
  if (pid_ > 0 && Running()) {
    kill(pid_, SIGKILL);
    Wait(std::chrono::seconds(10));
  }
  std::remove(stdout_path_.c_str());
  std::remove(stderr_path_.c_str());
}

std::string Subprocess::StdOut() const { return ReadFile(stdout_path_); }

std::string Subprocess::StdErr() const { return ReadFile(stderr_path_); }

bool Subprocess::WaitForOutput(const std::string& text, std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (Output().find(text) != std::string::npos) return true;
    if (!Running()) return Output().find(text) != std::string::npos;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

void Subprocess::Signal(int signal) const {
  if (pid_ > 0 && Running()) kill(pid_, signal);
}

bool Subprocess::Running() const {
  if (pid_ <= 0 || exit_code_.has_value()) return false;
  int status = 0;
  const pid_t done = waitpid(pid_, &status, WNOHANG);
  if (done == 0) return true;
  exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return false;
}

std::optional<int> Subprocess::Wait(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (Running()) {
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return exit_code_;
}

CommandResult RunCommand(std::vector<std::string> argv, std::chrono::milliseconds timeout) {
  Subprocess process(std::move(argv));
  CommandResult result;
  result.exit_code = process.Wait(timeout).value_or(-1);
  result.out = process.StdOut();
  result.err = process.StdErr();
  return result;
}

int RandomDomainId() {
  constexpr int kDomains = 200;
  std::random_device random;
  const int start = static_cast<int>(random() % kDomains);
  // Chance alone let two tests of a parallel ctest run meet (seen in CI): each candidate is
  // claimed with an exclusive lock on a file named after it, held (the descriptor stays open)
  // until this process exits. A second claim of the same id, even by this process, fails.
  for (int i = 0; i < kDomains; ++i) {
    const int domain = 1 + (start + i) % kDomains;
    if (ClaimDomainId(domain)) return domain;
  }
  return 1 + start;  // every id is claimed: fall back to chance
}

bool ClaimDomainId(int domain) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("fleetmap-dds-domain-" + std::to_string(domain) + ".lock"))
                               .string();
  const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) return false;
  if (flock(fd, LOCK_EX | LOCK_NB) == 0) return true;  // the descriptor stays open: the claim
  close(fd);
  return false;
}

std::optional<ProcessUsage> ReadUsage(pid_t pid) {
  const std::string proc = "/proc/" + std::to_string(pid);
  std::ifstream stat(proc + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return std::nullopt;
  // Fields after the command name, which is in parentheses and may hold spaces.
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream fields(line.substr(close + 2));
  std::vector<std::string> values;
  for (std::string value; fields >> value;) values.push_back(value);
  // utime and stime are fields 14 and 15 of the whole line: 12 and 13 after the name.
  if (values.size() < 13) return std::nullopt;
  const double ticks = static_cast<double>(sysconf(_SC_CLK_TCK));
  ProcessUsage usage;
  usage.cpu_seconds = (std::stod(values[11]) + std::stod(values[12])) / ticks;
  std::ifstream status(proc + "/status");
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) usage.peak_rss_bytes = std::stoll(line.substr(6)) * 1024;
    if (line.rfind("VmRSS:", 0) == 0) usage.rss_bytes = std::stoll(line.substr(6)) * 1024;
  }
  return usage;
}

}  // namespace fleetmap::process
