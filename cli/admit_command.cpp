#include "cli/admit_command.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

#include "cli/inputs/exit_codes.hpp"
#include "common/core/ids.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"

namespace fleetmap::cli {
namespace {

using SteadyClock = std::chrono::steady_clock;
using Standing = transport::RobotFrameMessage::Standing;

constexpr int kExitNoAnswer = 1;

std::string OperatorName(const AdmitOptions& options) {
  if (!options.operator_name.empty()) return options.operator_name;
  const char* user = std::getenv("USER");
  return user != nullptr ? user : "";
}

}  // namespace

int RunAdmit(const AdmitOptions& options, std::ostream& out, std::ostream& err) {
  const auto fail = [&](const std::string& message, int code) {
    err << "fleetmap admit: " << message << "\n";
    return code;
  };
  if (!IsValidRobotName(options.robot)) {
    return fail(fmt::format("\"{}\" is not a robot name (a ROS 2 name token of at most 64 "
                            "characters)",
                            options.robot.substr(0, 80)),
                kExitBadInput);
  }
  auto dds = options.fleet.Participant("fleetmap-admit");
  if (!dds.ok()) return fail(dds.status().message(), kExitBadInput);
  auto participant = transport::Participant::Create(*dds);
  if (!participant.ok()) return fail(participant.status().message(), kExitBadInput);
  const int domain = (*participant)->domain_id();
  auto wake_up = std::make_shared<WakeUp>();
  auto frames = transport::RobotFrameReader::Create(**participant, wake_up);
  if (!frames.ok()) return fail(frames.status().message(), kExitBadInput);
  auto writer = transport::RobotAdmissionWriter::Create(**participant);
  if (!writer.ok()) return fail(writer.status().message(), kExitBadInput);

  transport::RobotAdmissionMessage admission;
  admission.robot = RobotId{options.robot};
  admission.operator_name = OperatorName(options);
  std::map<RobotId, transport::RobotFrameMessage> known;
  bool written = false;
  std::optional<transport::RobotFrameMessage> before;  // the robot's frame before the admission
  const auto start = SteadyClock::now();
  const auto deadline = start + std::chrono::duration_cast<SteadyClock::duration>(
                                    std::chrono::duration<double>(options.timeout_s));
  while (SteadyClock::now() < deadline) {
    // The admission goes out once a server reads the topic (transient local would keep it for a
    // late server too, but only while this command runs).
    // It waits a moment for the robot's current frame (transient local, on its way from the
    // server), so that it can say what the admission changed.
    const bool frame_seen_or_late = before || SteadyClock::now() - start > std::chrono::seconds(2);
    if (!written && (*writer)->matched_readers() > 0 && frame_seen_or_late) {
      admission.stamp = Clock::now();
      if (StatusOr<size_t> sent = (*writer)->Write(admission); !sent.ok()) {
        return fail(sent.status().message(), kExitNoAnswer);
      }
      written = true;
    }
    wake_up->WaitFor(std::chrono::milliseconds(100));
    for (transport::RobotFrameEvent& event : (*frames)->Drain()) {
      if (event.kind != transport::RobotFrameEvent::Kind::kSample) continue;
      const transport::RobotFrameMessage& frame = event.message;
      if (frame.robot == admission.robot && !written && !before) before = frame;
      known[frame.robot] = frame;
    }
    const auto it = known.find(admission.robot);
    if (written && it != known.end() && it->second.standing == Standing::kAdmitted) {
      out << fmt::format("robot {} admitted{}: its tiles are fused from now on\n", options.robot,
                         before && before->standing == Standing::kQuarantined
                             ? " out of quarantine (" + before->standing_reason + ")"
                             : "");
      return kExitOk;
    }
  }
  if (!written) {
    return fail(fmt::format("no fleetmap-server reads {} on DDS domain {} (waited {:.0f} s): is "
                            "one running there (--domain, $FLEETMAP_DOMAIN), and in a secured "
                            "fleet, is --security given with the server's identity?",
                            transport::kAdmissionsTopic, domain, options.timeout_s),
                kExitNoAnswer);
  }
  std::string robots;
  for (const auto& [robot, frame] : known) robots += (robots.empty() ? "" : ", ") + robot.value;
  return fail(
      fmt::format("the server did not report {} admitted within {:.0f} s on DDS domain "
                  "{}; robots it reports: {}",
                  options.robot, options.timeout_s, domain, robots.empty() ? "none" : robots),
      kExitNoAnswer);
}

void AddAdmitCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<AdmitOptions>();
  CLI::App* command = app.add_subcommand(
      "admit", "Admit a quarantined robot's map into the fused map (docs/fleet.md, Quarantine)");
  command->add_option("robot", options->robot, "the robot id")->required();
  command->add_option("--operator", options->operator_name,
                      "who admits it, for the server's log (default: $USER)");
  command->add_option("--timeout", options->timeout_s, "seconds to wait for the server's answer")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  auto fleet = std::make_shared<FleetReaderFlags>(command, &options->fleet);
  command->callback([options, fleet, exit_code] {
    fleet->ApplyDomain();
    *exit_code = RunAdmit(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::cli
