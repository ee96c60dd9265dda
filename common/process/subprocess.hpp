#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fleetmap::process {

// A child process (a fleetmap-server, an agent, a tool under test): started with posix_spawn, its
// stdout and stderr captured in temporary files that the parent can poll. Killed (SIGKILL) on
// destruction if still running. Use from one thread.
class Subprocess {
 public:
  // `env` entries are added to (or override) the test's own environment.
  Subprocess(std::vector<std::string> argv, std::map<std::string, std::string> env = {});
  ~Subprocess();
  Subprocess(const Subprocess&) = delete;
  Subprocess& operator=(const Subprocess&) = delete;

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }

  // What the process printed so far: on stdout, on stderr, and both (stdout first).
  std::string StdOut() const;
  std::string StdErr() const;
  std::string Output() const { return StdOut() + StdErr(); }
  // Waits until Output() contains `text`; false on timeout or if the process exited without it.
  bool WaitForOutput(const std::string& text, std::chrono::milliseconds timeout) const;

  void Signal(int signal) const;
  // The exit code (or 128 + signal), or nullopt if still running after `timeout`.
  std::optional<int> Wait(std::chrono::milliseconds timeout);

 private:
  bool Running() const;

  pid_t pid_ = -1;
  std::string stdout_path_;
  std::string stderr_path_;
  mutable std::optional<int> exit_code_;
};

// The result of running a command to completion.
struct CommandResult {
  int exit_code = -1;  // 128 + signal if killed, -1 if it did not finish in time
  std::string out;
  std::string err;
  std::string output() const { return out + err; }
};

CommandResult RunCommand(std::vector<std::string> argv,
                         std::chrono::milliseconds timeout = std::chrono::seconds(60));

// A DDS domain id for one run or test that no other process on this machine holds (claimed with a
// lock file in the temp directory until this process exits), starting from a random id, so that
// runs in parallel never meet.
int RandomDomainId();

// Claims `domain` as RandomDomainId does (until this process exits); false if another claim holds
// it. For a test that needs a second, chosen domain, such as the neighbour of a random one.
bool ClaimDomainId(int domain);

// Resource use of a running process, from /proc: CPU seconds (user + system), resident memory now
// (VmRSS) and its peak (VmHWM), or nullopt once it is gone.
struct ProcessUsage {
  double cpu_seconds = 0.0;
  int64_t rss_bytes = 0;
  int64_t peak_rss_bytes = 0;
};
std::optional<ProcessUsage> ReadUsage(pid_t pid);

}  // namespace fleetmap::process
