#pragma once

// `fleetmap security init|enroll|revoke|show --dir D`: the fleet's DDS Security folder, so that no
// one has to learn openssl and the governance XML (common/security, docs/security.md).

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>

namespace fleetmap::cli {

struct SecurityCommandOptions {
  std::string action;  // init, enroll, revoke, show
  std::string dir;
  std::string robot;   // enroll / revoke: a robot id
  std::string viewer;  // enroll / revoke: a read-only identity's name
  int days = 365;      // enroll / init: an identity's validity
  int ca_days = 3650;  // init: the CA's
  bool json = false;   // show
};

// Runs one action; what it did goes to `out`, errors (naming the file and the problem) to `err`.
// Returns kExitOk, or kExitBadInput.
int RunSecurity(const SecurityCommandOptions& options, std::ostream& out, std::ostream& err);

// Registers the `security` subcommand (and its init, enroll, revoke and show) on `app`.
void AddSecurityCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
