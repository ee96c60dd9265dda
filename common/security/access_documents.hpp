#pragma once

// The two access-control documents of DDS Security, as fleetmap writes them (unsigned XML; the
// fleet CA signs them): the governance (what the fleet's domains protect) and one identity's
// permissions (what it may publish and subscribe). docs/security.md explains every rule.

#include <ctime>
#include <optional>
#include <string>

namespace fleetmap::security {

// What an identity is in the fleet; its certificate says so (subject OU).
enum class Role {
  kServer,  // fleetmap-server: reads the robots, alone writes the fused topics
  kRobot,   // a fleetmap-agent: writes its own tiles, status, entities and grid, reads the fused
  kViewer,  // a tool that watches (fleetmap view, save-map, the sim's observer): reads everything
};

const char* RoleName(Role role);
std::optional<Role> ParseRole(const std::string& name);

// The topics only the server may write, and the robot-owned topics every robot writes in the DDS
// partition named after itself (transport puts a secured robot's publisher there).
inline constexpr const char* kServerTopics[] = {
    "rt/fleetmap/fused_tiles",      "rt/fleetmap/map",     "rt/fleetmap/submap_graph",
    "rt/fleetmap/object_templates", "rt/fleetmap/objects", "rt/fleetmap/robot_frames",
    "rt/fleetmap/admissions",       "rt/fleetmap/servers", "rt/tf"};
inline constexpr const char* kRobotOwnedTopics[] = {
    "rt/fleetmap/robot_tiles", "rt/fleetmap/robot_status", "rt/fleetmap/entities"};

// The governance: every DDS domain (0..232) refuses unauthenticated participants and checks
// joins; discovery and liveliness are encrypted, RTPS messages signed, and every topic's data and
// metadata encrypted with read and write access control (the SROS2 defaults).
std::string GovernanceXml();

// The permissions of one identity (`subject` in RFC 2253 form, exactly as its certificate's),
// valid from `not_before` to `not_after`. `revoked`: a grant that allows nothing (DENY only).
struct PermissionsRequest {
  std::string name;
  Role role = Role::kRobot;
  std::string subject;
  std::time_t not_before = 0;
  std::time_t not_after = 0;
  bool revoked = false;
};
std::string PermissionsXml(const PermissionsRequest& request);

}  // namespace fleetmap::security
