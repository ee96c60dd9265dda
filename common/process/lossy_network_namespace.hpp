#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::process {

// A lossy network on one machine, for tests and benchmarks: a network namespace of its own
// (loopback up, nothing else) whose nftables output hook drops `loss_percent` % of the UDP
// datagrams at random. Needs root, `ip` (iproute2) and `nft` (nftables). Destruction deletes the
// rule and the namespace, however the test ended; processes still inside keep running, cut off.
//
// Fleet processes must use UDP inside it (`--localhost-only`): shared memory between processes
// would bypass the loss. Use from one thread.
class LossyNetworkNamespace {
 public:
  // OK when this process can make one; otherwise what is missing (not root, no ip, no nft).
  static Status CheckAvailable();
  // A new namespace named uniquely for this process and call. Unavailable when this machine
  // cannot make one (CheckAvailable's reasons, or no CAP_SYS_ADMIN); Internal when one was made
  // but the rule could not be set.
  static StatusOr<std::unique_ptr<LossyNetworkNamespace>> Create(int loss_percent);
  ~LossyNetworkNamespace();
  LossyNetworkNamespace(const LossyNetworkNamespace&) = delete;
  LossyNetworkNamespace& operator=(const LossyNetworkNamespace&) = delete;

  const std::string& name() const { return name_; }
  int loss_percent() const { return loss_percent_; }

  // The argv prefix that runs a program inside: {ip, netns, exec, name}.
  std::vector<std::string> ExecPrefix() const;

  // While alive, the calling thread is inside the namespace; sockets it opens, and threads and
  // processes it starts (a DDS participant's, posix_spawn children), belong there. Destruction
  // moves the thread back to where it was.
  class Inside {
   public:
    ~Inside();
    Inside(const Inside&) = delete;
    Inside& operator=(const Inside&) = delete;

   private:
    friend class LossyNetworkNamespace;
    explicit Inside(int previous_fd) : previous_fd_(previous_fd) {}
    int previous_fd_ = -1;
  };
  StatusOr<std::unique_ptr<Inside>> Enter() const;

 private:
  LossyNetworkNamespace(std::string ip, std::string nft, std::string name, int loss_percent)
      : ip_(std::move(ip)),
        nft_(std::move(nft)),
        name_(std::move(name)),
        loss_percent_(loss_percent) {}

  // Runs `argv` inside the namespace; an error names the command and what it printed.
  Status RunInside(std::vector<std::string> argv) const;

  std::string ip_;
  std::string nft_;
  std::string name_;
  int loss_percent_ = 0;
  bool namespace_added_ = false;
  bool table_added_ = false;
};

// The absolute path of `program` on $PATH or in /usr/sbin and /sbin, or empty.
std::string FindProgram(const std::string& program);

}  // namespace fleetmap::process
