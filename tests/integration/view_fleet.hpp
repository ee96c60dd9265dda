#pragma once

// A live fleet for the web view's tests: a fleetmap-server, agents on a real map and `fleetmap
// view` on a random domain, all real processes over DDS on loopback.

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"
#include "common/transport/participant.hpp"
#include "tests/integration/fleet_binaries.hpp"
#include "tests/integration/loopback_participant.hpp"

namespace fleetmap::testing {

inline const std::string kViewTestMap =
    std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/real/aws_small_house.yaml";

// `fleetmap view --port <port>` on `domain` (port 0: any free one); port() is read from the URL
// it prints.
class ViewProcess {
 public:
  ViewProcess(int domain, std::vector<std::string> extra_args = {}, int port = 0) {
    std::vector<std::string> argv = {std::string(FLEETMAP_BINARY_DIR) + "/cli/fleetmap",
                                     "view",
                                     "--port",
                                     std::to_string(port),
                                     "--domain",
                                     std::to_string(domain),
                                     "--localhost-only"};
    argv.insert(argv.end(), extra_args.begin(), extra_args.end());
    process_ = std::make_unique<process::Subprocess>(std::move(argv));
    if (!process_->WaitForOutput("open http://", std::chrono::seconds(30))) return;
    std::smatch match;
    const std::string output = process_->StdOut();
    if (std::regex_search(output, match, std::regex(R"(http://127\.0\.0\.1:(\d+)/)"))) {
      port_ = std::stoi(match[1]);
    }
  }
  int port() const { return port_; }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/"; }
  process::Subprocess& process() { return *process_; }

 private:
  std::unique_ptr<process::Subprocess> process_;
  int port_ = 0;
};

// A server and `robots` agents on the small house, 1.5 m apart so that their dots do not hide
// each other.
class LiveFleet {
 public:
  LiveFleet(int domain, const std::vector<std::string>& robots)
      : env_({{"FLEETMAP_DOMAIN", std::to_string(domain)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}}) {
    server_ = std::make_unique<process::Subprocess>(
        std::vector<std::string>{kServerBinary, "--duration", "300", "--no-object-learning",
                                 "--no-extrapolation", "--map-period", "0.5"},
        env_);
    for (size_t i = 0; i < robots.size(); ++i) {
      agents_[robots[i]] = std::make_unique<process::Subprocess>(
          std::vector<std::string>{kAgentBinary, "--robot-id", robots[i], "--map", kViewTestMap,
                                   "--pose", std::to_string(1.5 * static_cast<double>(i)), "0",
                                   "0"},
          env_);
    }
  }
  process::Subprocess& server() { return *server_; }
  process::Subprocess& agent(const std::string& robot) { return *agents_.at(robot); }

 private:
  std::map<std::string, std::string> env_;
  std::unique_ptr<process::Subprocess> server_;
  std::map<std::string, std::unique_ptr<process::Subprocess>> agents_;
};

}  // namespace fleetmap::testing
