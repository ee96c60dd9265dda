#include "common/process/lossy_network_namespace.hpp"

#include <fcntl.h>
#include <sched.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "common/process/subprocess.hpp"

namespace fleetmap::process {
namespace {

constexpr char kTable[] = "fmloss";
constexpr std::chrono::seconds kCommandTimeout{20};

std::string Join(const std::vector<std::string>& argv) {
  std::ostringstream out;
  for (size_t i = 0; i < argv.size(); ++i) out << (i > 0 ? " " : "") << argv[i];
  return out.str();
}

Status Run(const std::vector<std::string>& argv) {
  const CommandResult result = RunCommand(argv, kCommandTimeout);
  if (result.exit_code == 0) return Status::Ok();
  // Appended piece by piece: GCC 12 warns (-Wrestrict) about "literal" + std::string&&.
  std::string message = "`";
  message += Join(argv);
  message += "` failed (exit ";
  message += std::to_string(result.exit_code);
  message += "): ";
  message += result.output();
  return UnavailableError(std::move(message));
}

}  // namespace

std::string FindProgram(const std::string& program) {
  std::vector<std::string> dirs;
  if (const char* path = std::getenv("PATH"); path != nullptr) {
    std::istringstream in(path);
    for (std::string dir; std::getline(in, dir, ':');) {
      if (!dir.empty()) dirs.push_back(dir);
    }
  }
  dirs.insert(dirs.end(), {"/usr/sbin", "/sbin", "/usr/bin", "/bin"});
  for (const std::string& dir : dirs) {
    const std::string candidate = dir + "/" + program;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

Status LossyNetworkNamespace::CheckAvailable() {
  if (geteuid() != 0) return UnavailableError("needs root (network namespaces, nftables)");
  if (FindProgram("ip").empty()) return UnavailableError("needs `ip` (Debian package iproute2)");
  if (FindProgram("nft").empty()) return UnavailableError("needs `nft` (Debian package nftables)");
  return Status::Ok();
}

StatusOr<std::unique_ptr<LossyNetworkNamespace>> LossyNetworkNamespace::Create(int loss_percent) {
  FLEETMAP_RETURN_IF_ERROR(CheckAvailable());
  if (loss_percent < 0 || loss_percent > 100) {
    return InvalidArgumentError("a loss of " + std::to_string(loss_percent) +
                                " % is outside 0..100");
  }
  static std::atomic<int> counter{0};
  const std::string name =
      "fmloss-" + std::to_string(getpid()) + "-" + std::to_string(counter.fetch_add(1));
  std::unique_ptr<LossyNetworkNamespace> self(
      new LossyNetworkNamespace(FindProgram("ip"), FindProgram("nft"), name, loss_percent));
  // Each step is recorded as soon as it succeeds, so the destructor undoes exactly what was made.
  // Unavailable: this machine cannot make namespaces (a container without CAP_SYS_ADMIN); any
  // later failure is Internal, a broken set-up that a test must not skip quietly.
  FLEETMAP_RETURN_IF_ERROR(Run({self->ip_, "netns", "add", name}));
  self->namespace_added_ = true;
  const auto internal = [](const Status& status) {
    return status.ok() ? status : InternalError(status.message());
  };
  FLEETMAP_RETURN_IF_ERROR(internal(self->RunInside({self->ip_, "link", "set", "lo", "up"})));
  FLEETMAP_RETURN_IF_ERROR(internal(self->RunInside({self->nft_, "add", "table", "inet", kTable})));
  self->table_added_ = true;
  FLEETMAP_RETURN_IF_ERROR(
      internal(self->RunInside({self->nft_, "add", "chain", "inet", kTable, "out",
                                "{ type filter hook output priority 0 ; policy accept ; }"})));
  // Every datagram on loopback passes the output hook once: each is dropped with probability
  // loss_percent / 100, independently (RTPS fragments are datagrams of their own).
  std::vector<std::string> rule = {self->nft_, "add",  "rule",    "inet", kTable,
                                   "out",      "meta", "l4proto", "udp"};
  if (loss_percent < 100) {
    rule.insert(rule.end(), {"numgen", "random", "mod", "100", "<", std::to_string(loss_percent)});
  }
  rule.push_back("drop");
  if (loss_percent > 0) FLEETMAP_RETURN_IF_ERROR(internal(self->RunInside(rule)));
  return self;
}

LossyNetworkNamespace::~LossyNetworkNamespace() {
  // Best effort: a failure here has nobody to report to, and the next step still runs.
  if (table_added_) (void)RunInside({nft_, "delete", "table", "inet", kTable});
  if (namespace_added_) (void)Run({ip_, "netns", "delete", name_});
}

std::vector<std::string> LossyNetworkNamespace::ExecPrefix() const {
  return {ip_, "netns", "exec", name_};
}

Status LossyNetworkNamespace::RunInside(std::vector<std::string> argv) const {
  std::vector<std::string> full = ExecPrefix();
  full.insert(full.end(), argv.begin(), argv.end());
  return Run(full);
}

StatusOr<std::unique_ptr<LossyNetworkNamespace::Inside>> LossyNetworkNamespace::Enter() const {
  const int previous = open("/proc/thread-self/ns/net", O_RDONLY | O_CLOEXEC);
  if (previous < 0) {
    return UnavailableError(std::string("cannot open this thread's network namespace: ") +
                            std::strerror(errno));
  }
  const std::string path = "/run/netns/" + name_;
  const int target = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (target < 0) {
    const int error = errno;
    close(previous);
    return UnavailableError("cannot open " + path + ": " + std::strerror(error));
  }
  const int entered = setns(target, CLONE_NEWNET);
  const int error = errno;
  close(target);
  if (entered != 0) {
    close(previous);
    return UnavailableError("cannot enter network namespace " + name_ + ": " +
                            std::strerror(error));
  }
  return std::unique_ptr<Inside>(new Inside(previous));
}

LossyNetworkNamespace::Inside::~Inside() {
  // Failing to go back would leave this thread cut off from the host's network: a broken
  // invariant of everything that runs on it afterwards.
  if (setns(previous_fd_, CLONE_NEWNET) != 0) {
    std::fprintf(stderr, "LossyNetworkNamespace: cannot return to the previous namespace: %s\n",
                 std::strerror(errno));
    std::abort();
  }
  close(previous_fd_);
}

}  // namespace fleetmap::process
