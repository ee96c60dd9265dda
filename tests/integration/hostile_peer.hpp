#pragma once

// The hostile peer (tests/hostile_peer, docs/testing.md) as the integration tests start it: a
// Cyclone DDS participant, loopback only, on the test's domain.
//
//   auto peer = testing::HostilePeer::Start(domain, {"--far-key", "--duration", "30"});
//   ASSERT_TRUE(peer->WaitForOutput("sent 1 tiles", std::chrono::seconds(10)));

#include <memory>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"

namespace fleetmap::testing {

inline const std::string kHostilePeerBinary =
    std::string(FLEETMAP_BINARY_DIR) + "/tests/hostile_peer/fleetmap-hostile-peer";

struct HostilePeer {
  // Starts fleetmap-hostile-peer on `domain` with the scenario options `args` (see
  // `fleetmap-hostile-peer --help`); it stays for --duration (default 10 s), then exits 0.
  static std::unique_ptr<process::Subprocess> Start(int domain,
                                                    const std::vector<std::string>& args) {
    std::vector<std::string> argv = {kHostilePeerBinary, "--domain", std::to_string(domain)};
    argv.insert(argv.end(), args.begin(), args.end());
    return std::make_unique<process::Subprocess>(std::move(argv));
  }
};

}  // namespace fleetmap::testing
