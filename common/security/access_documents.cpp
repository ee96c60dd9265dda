#include "common/security/access_documents.hpp"

#include <fmt/format.h>

#include <vector>

#include "common/security/utc_time.hpp"

namespace fleetmap::security {
namespace {

constexpr char kHeader[] =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
    "xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-SECURITY/20170901/"
    "omg_shared_ca_{}.xsd\">\n";

// All the domains a fleetmap participant may use (participant.hpp: 0..232).
constexpr char kAllDomains[] = "<domains><id_range><min>0</min><max>232</max></id_range></domains>";

// Fast DDS 2.9 reads the validity dates as local time (std::mktime), and the XML has no zone:
// on a machine behind UTC a grant starting now would start hours from now. A day's slack covers
// every zone; the certificate's own dates (UTC) still bound the identity.
constexpr std::time_t kLocalTimeSlack = 86400;

std::string Utc(std::time_t time) { return FormatUtc(time, "%Y-%m-%dT%H:%M:%S"); }

// One <publish> or <subscribe> criterion: the topics, in the partitions (none: the default one).
std::string Criterion(const char* kind, const std::vector<std::string>& topics,
                      const std::vector<std::string>& partitions) {
  std::string xml = fmt::format("        <{}>\n          <topics>", kind);
  for (const std::string& topic : topics) xml += fmt::format("<topic>{}</topic>", topic);
  xml += "</topics>\n";
  if (!partitions.empty()) {
    xml += "          <partitions>";
    for (const std::string& partition : partitions) {
      xml += fmt::format("<partition>{}</partition>", partition);
    }
    xml += "</partitions>\n";
  }
  xml += fmt::format("        </{}>\n", kind);
  return xml;
}

std::vector<std::string> Strings(const auto& topics) {
  return std::vector<std::string>(std::begin(topics), std::end(topics));
}

// The allow rule of a role. Subscriptions use the partitions "" and "*" (transport's secured
// subscriber): "*" matches every partition, the default one included.
std::string AllowRule(const PermissionsRequest& request) {
  const std::vector<std::string> any_partition = {"*"};
  std::string criteria;
  switch (request.role) {
    case Role::kServer:
      criteria += Criterion("publish", Strings(kServerTopics), {});
      criteria += Criterion("subscribe", Strings(kRobotOwnedTopics), any_partition);
      // Operators admit quarantined robots with the server's identity (`fleetmap admit`).
      criteria += Criterion("subscribe", {"rt/fleetmap/admissions"}, any_partition);
      // A standby follows the servers it stands by for.
      criteria += Criterion("subscribe", {"rt/fleetmap/servers"}, any_partition);
      // The robots' own grids and their patches: rt/<robot>/map, _updates, _updates_zstd.
      criteria += Criterion("subscribe", {"rt/*/map", "rt/*/map_updates", "rt/*/map_updates_zstd"},
                            any_partition);
      break;
    case Role::kRobot: {
      std::vector<std::string> own = Strings(kRobotOwnedTopics);
      for (const char* suffix : {"/map", "/map_updates", "/map_updates_zstd"}) {
        own.push_back("rt/" + request.name + suffix);
      }
      criteria += Criterion("publish", own, {request.name});
      // What an agent reads: the fused topics, and the statuses (a second agent claiming its id).
      std::vector<std::string> reads = Strings(kServerTopics);
      reads.push_back("rt/fleetmap/robot_status");
      criteria += Criterion("subscribe", reads, any_partition);
      break;
    }
    case Role::kViewer:
      criteria += Criterion("subscribe", {"*"}, any_partition);
      break;
  }
  return fmt::format("      <allow_rule>\n        {}\n{}      </allow_rule>\n", kAllDomains,
                     criteria);
}

}  // namespace

const char* RoleName(Role role) {
  switch (role) {
    case Role::kServer:
      return "server";
    case Role::kRobot:
      return "robot";
    case Role::kViewer:
      return "viewer";
  }
  return "?";
}

std::optional<Role> ParseRole(const std::string& name) {
  for (Role role : {Role::kServer, Role::kRobot, Role::kViewer}) {
    if (name == RoleName(role)) return role;
  }
  return std::nullopt;
}

std::string GovernanceXml() {
  std::string xml = fmt::format(kHeader, "governance");
  xml += fmt::format(
      "  <domain_access_rules>\n"
      "    <domain_rule>\n"
      "      {}\n"
      "      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
      "      <enable_join_access_control>true</enable_join_access_control>\n"
      "      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>\n"
      "      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>\n"
      "      <rtps_protection_kind>SIGN</rtps_protection_kind>\n"
      "      <topic_access_rules>\n"
      "        <topic_rule>\n"
      "          <topic_expression>*</topic_expression>\n"
      "          <enable_discovery_protection>true</enable_discovery_protection>\n"
      "          <enable_liveliness_protection>true</enable_liveliness_protection>\n"
      "          <enable_read_access_control>true</enable_read_access_control>\n"
      "          <enable_write_access_control>true</enable_write_access_control>\n"
      "          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>\n"
      "          <data_protection_kind>ENCRYPT</data_protection_kind>\n"
      "        </topic_rule>\n"
      "      </topic_access_rules>\n"
      "    </domain_rule>\n"
      "  </domain_access_rules>\n",
      kAllDomains);
  xml += "</dds>\n";
  return xml;
}

std::string PermissionsXml(const PermissionsRequest& request) {
  std::string xml = fmt::format(kHeader, "permissions");
  xml += fmt::format(
      "  <permissions>\n"
      "    <grant name=\"{}_{}\">\n"
      "      <subject_name>{}</subject_name>\n"
      "      <validity><not_before>{}</not_before><not_after>{}</not_after></validity>\n",
      RoleName(request.role), request.name, request.subject,
      Utc(request.not_before - kLocalTimeSlack), Utc(request.not_after));
  if (!request.revoked) xml += AllowRule(request);
  xml +=
      "      <default>DENY</default>\n"
      "    </grant>\n"
      "  </permissions>\n"
      "</dds>\n";
  return xml;
}

}  // namespace fleetmap::security
