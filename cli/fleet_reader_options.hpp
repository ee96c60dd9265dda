#pragma once

// How the tool's commands that join a running fleet as a reader (save-map, view) reach it: the
// DDS domain, loopback only, discovery servers, and a secured fleet's viewer identity. One set of
// options, spelled the same on every such command.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "common/core/status.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::cli {

struct FleetReaderOptions {
  std::optional<int> domain;  // unset: $FLEETMAP_DOMAIN, else 0
  bool localhost_only = false;
  std::optional<std::string> discovery_server;  // unset: $ROS_DISCOVERY_SERVER, else simple
  std::string security_dir;                     // join a secured fleet
  std::string security_identity = "viewer";     // ... as this enrolled viewer

  // The participant's options, named `name`; errors name --security and what is wrong with the
  // folder or the identity.
  StatusOr<transport::ParticipantOptions> Participant(const std::string& name) const;
};

// --domain, --localhost-only, --discovery-server, --security, --identity. The domain is only set
// when given, so the environment still applies; call ApplyDomain in the command's callback.
class FleetReaderFlags {
 public:
  FleetReaderFlags(CLI::App* command, FleetReaderOptions* options);
  void ApplyDomain() const;

 private:
  FleetReaderOptions* options_;
  std::shared_ptr<int> domain_ = std::make_shared<int>(-1);
};

}  // namespace fleetmap::cli
