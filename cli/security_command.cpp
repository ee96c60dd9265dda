#include "cli/security_command.hpp"

#include <fmt/format.h>

#include <ctime>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/inputs/exit_codes.hpp"
#include "common/security/fleet_security.hpp"
#include "common/security/security_folder.hpp"
#include "common/security/utc_time.hpp"

namespace fleetmap::cli {
namespace {

constexpr char kDescription[] = R"(
A secured fleet runs DDS Security: every participant authenticates with a certificate of the
fleet CA, traffic is encrypted, and signed permissions say who may write what. Steps:
  fleetmap security init --dir D               the CA, governance and the server's identity
  fleetmap security enroll --dir D --robot R   robot R (writes only its own topics)
  fleetmap security enroll --dir D --viewer V  a read-only tool
  fleetmap-server --security D ; fleetmap-agent --robot-id R --security D
  fleetmap security revoke --dir D --robot R   R refused from each participant's next start
  fleetmap security show --dir D               who is enrolled, until when
Keys are written 0600. docs/security.md describes the folder and the permissions.)";

std::string UtcDate(std::time_t time) { return security::FormatUtc(time, "%Y-%m-%d %H:%M"); }

int Fail(std::ostream& err, const std::string& message) {
  err << "fleetmap security: " << message << "\n";
  return kExitBadInput;
}

int Show(const SecurityCommandOptions& options, std::ostream& out, std::ostream& err) {
  const auto identities = security::ListIdentities(options.dir);
  if (!identities.ok()) return Fail(err, identities.status().message());
  const std::time_t now = std::time(nullptr);
  const auto state = [now](const security::EnrolledIdentity& identity) {
    if (identity.revoked) return "revoked";
    if (identity.not_after < now) return "expired";
    if (identity.not_before > now) return "not yet valid";
    return "valid";
  };
  if (options.json) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& identity : *identities) {
      list.push_back({{"name", identity.name},
                      {"role", identity.role},
                      {"serial", identity.serial},
                      {"not_before", UtcDate(identity.not_before)},
                      {"not_after", UtcDate(identity.not_after)},
                      {"state", state(identity)}});
    }
    out << nlohmann::json{{"dir", options.dir}, {"identities", list}}.dump() << "\n";
    return kExitOk;
  }
  out << fmt::format("{:<20} {:<7} {:<17} {:<17} {}\n", "name", "role", "valid from",
                     "valid until (UTC)", "state");
  for (const auto& identity : *identities) {
    out << fmt::format("{:<20} {:<7} {:<17} {:<17} {}\n", identity.name, identity.role,
                       UtcDate(identity.not_before), UtcDate(identity.not_after), state(identity));
  }
  return kExitOk;
}

}  // namespace

int RunSecurity(const SecurityCommandOptions& options, std::ostream& out, std::ostream& err) {
  const security::SecurityFolder folder(options.dir);
  if (options.action == "init") {
    security::FleetSecurityOptions settings;
    settings.ca_days = options.ca_days;
    settings.identity_days = options.days;
    if (const Status made = security::InitFleet(options.dir, settings); !made.ok()) {
      return Fail(err, made.message());
    }
    out << "made the fleet CA " << folder.ca_cert().string() << " (its key "
        << folder.ca_key().string() << ", 0600: keep it off the robots), the signed governance "
        << folder.governance().string() << ", the revocation list " << folder.crl().string()
        << " and the server's identity " << folder.identity(security::kServerIdentity).string()
        << "\n";
    return kExitOk;
  }
  if (options.action == "show") return Show(options, out, err);

  if (options.robot.empty() == options.viewer.empty()) {
    return Fail(err, options.action + ": give exactly one of --robot and --viewer");
  }
  const std::string name = options.robot.empty() ? options.viewer : options.robot;
  if (options.action == "enroll") {
    const security::Role role =
        options.robot.empty() ? security::Role::kViewer : security::Role::kRobot;
    if (const Status enrolled =
            security::Enroll(options.dir, name, role, security::Validity::FromNow(options.days));
        !enrolled.ok()) {
      return Fail(err, enrolled.message());
    }
    out << "enrolled " << security::RoleName(role) << " " << name << " for " << options.days
        << " days: " << folder.identity(name).string()
        << " (copy it, with ca/ca.pem, governance.p7s and crl.pem, to the "
        << security::RoleName(role) << "'s machine)\n";
    return kExitOk;
  }
  if (options.action == "revoke") {
    if (const Status revoked = security::Revoke(options.dir, name); !revoked.ok()) {
      return Fail(err, revoked.message());
    }
    out << "revoked " << name << ": its certificate is on " << folder.crl().string()
        << " and its permissions allow nothing; participants refuse it from their next start "
           "with the new list (copy crl.pem to them and restart them)\n";
    return kExitOk;
  }
  return Fail(err, "unknown action \"" + options.action + "\"");
}

void AddSecurityCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<SecurityCommandOptions>();
  CLI::App* command =
      app.add_subcommand("security", "Make and manage the fleet's DDS Security folder");
  command->footer(kDescription);
  command->require_subcommand(1);
  const auto add_action = [&](const std::string& action, const std::string& help) {
    CLI::App* sub = command->add_subcommand(action, help);
    sub->add_option("--dir", options->dir, "the fleet security folder")->required();
    sub->callback([options, exit_code, action]() {
      options->action = action;
      *exit_code = RunSecurity(*options, std::cout, std::cerr);
    });
    return sub;
  };
  CLI::App* init = add_action("init", "Make the fleet CA, the governance and the server identity");
  init->add_option("--days", options->days, "days the server's identity is valid")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  init->add_option("--ca-days", options->ca_days, "days the CA is valid")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  CLI::App* enroll = add_action("enroll", "Enroll a robot (or a read-only viewer)");
  enroll->add_option("--robot", options->robot, "robot id: it may write only its own topics");
  enroll->add_option("--viewer", options->viewer, "name of a tool that may only read");
  enroll->add_option("--days", options->days, "days the identity is valid")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  CLI::App* revoke = add_action("revoke", "Revoke a robot's (or a viewer's) identity");
  revoke->add_option("--robot", options->robot, "robot id");
  revoke->add_option("--viewer", options->viewer, "viewer name");
  CLI::App* show = add_action("show", "List who is enrolled, their roles and expiry dates");
  show->add_flag("--json", options->json, "one JSON line instead of a table");
}

}  // namespace fleetmap::cli
