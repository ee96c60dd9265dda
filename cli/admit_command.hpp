#pragma once

// `fleetmap admit ROBOT`: an operator's word that a quarantined robot's map is right (the
// building changed, or the robot was relocalized by hand). Publishes an admission on
// rt/fleetmap/admissions and waits until the server says on rt/fleetmap/robot_frames that the
// robot is admitted (docs/fleet.md, "Quarantine"). In a secured fleet it joins with the server's
// identity: only the server role may publish admissions.

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>

#include "cli/fleet_reader_options.hpp"

namespace fleetmap::cli {

struct AdmitOptions {
  std::string robot;
  std::string operator_name;  // for the server's log (default: $USER)
  double timeout_s = 15.0;    // for the server's answer
  FleetReaderOptions fleet = [] {
    FleetReaderOptions fleet;
    fleet.security_identity = "server";
    return fleet;
  }();
};

// kExitOk once the server reports the robot admitted; kExitBadInput for a bad robot name or
// options; 1 when no server answered within the timeout (the message says what it saw).
int RunAdmit(const AdmitOptions& options, std::ostream& out, std::ostream& err);

void AddAdmitCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::cli
