#include "common/security/access_documents.hpp"

#include <gtest/gtest.h>

#include <string>

#include "common/security/security_identity.hpp"

namespace fleetmap::security {
namespace {

// The text of the first <kind>...</kind> element of `xml`, or "".
std::string Element(const std::string& xml, const std::string& kind) {
  const size_t begin = xml.find("<" + kind + ">");
  const size_t end = xml.find("</" + kind + ">");
  if (begin == std::string::npos || end == std::string::npos) return "";
  return xml.substr(begin, end - begin);
}

PermissionsRequest Request(const std::string& name, Role role) {
  return PermissionsRequest{
      name,          role,          "CN=" + name + ",OU=" + RoleName(role) + ",O=fleetmap",
      1'800'000'000, 1'900'000'000, false};
}

TEST(AccessDocumentsTest, GovernanceRefusesTheUnauthenticatedAndEncryptsEverything) {
  const std::string xml = GovernanceXml();
  EXPECT_NE(xml.find("<allow_unauthenticated_participants>false<"), std::string::npos);
  EXPECT_NE(xml.find("<enable_join_access_control>true<"), std::string::npos);
  EXPECT_NE(xml.find("<discovery_protection_kind>ENCRYPT<"), std::string::npos);
  EXPECT_NE(xml.find("<liveliness_protection_kind>ENCRYPT<"), std::string::npos);
  EXPECT_NE(xml.find("<data_protection_kind>ENCRYPT<"), std::string::npos);
  EXPECT_NE(xml.find("<enable_write_access_control>true<"), std::string::npos);
  EXPECT_NE(xml.find("<enable_read_access_control>true<"), std::string::npos);
}

TEST(AccessDocumentsTest, ARobotPublishesOnlyItsOwnTopicsInItsOwnPartition) {
  const std::string xml = PermissionsXml(Request("alpha", Role::kRobot));
  EXPECT_NE(xml.find("<subject_name>CN=alpha,OU=robot,O=fleetmap</subject_name>"),
            std::string::npos);
  // A day early: Fast DDS reads the dates as local time.
  EXPECT_NE(xml.find("<not_before>2027-01-14T08:00:00</not_before>"), std::string::npos);
  const std::string publish = Element(xml, "publish");
  EXPECT_NE(publish.find("<topic>rt/fleetmap/robot_tiles</topic>"), std::string::npos);
  EXPECT_NE(publish.find("<topic>rt/alpha/map</topic>"), std::string::npos);
  EXPECT_NE(publish.find("<partition>alpha</partition>"), std::string::npos);
  for (const char* server_topic : kServerTopics) {
    EXPECT_EQ(publish.find(std::string("<topic>") + server_topic + "</topic>"), std::string::npos)
        << server_topic;
  }
  EXPECT_EQ(publish.find("*"), std::string::npos) << "no wildcard in what a robot may write";
  EXPECT_NE(Element(xml, "subscribe").find("<topic>rt/fleetmap/fused_tiles</topic>"),
            std::string::npos);
  EXPECT_NE(xml.find("<default>DENY</default>"), std::string::npos);
}

TEST(AccessDocumentsTest, OnlyTheServerPublishesTheFusedTopics) {
  const std::string server = Element(PermissionsXml(Request("server", Role::kServer)), "publish");
  for (const char* topic : kServerTopics) {
    EXPECT_NE(server.find(std::string("<topic>") + topic + "</topic>"), std::string::npos) << topic;
  }
  EXPECT_EQ(server.find("robot_tiles"), std::string::npos);
}

TEST(AccessDocumentsTest, AViewerOnlyReads) {
  const std::string xml = PermissionsXml(Request("watch", Role::kViewer));
  EXPECT_EQ(xml.find("<publish>"), std::string::npos);
  EXPECT_NE(xml.find("<subscribe>"), std::string::npos);
}

TEST(AccessDocumentsTest, ARevokedGrantAllowsNothing) {
  PermissionsRequest request = Request("alpha", Role::kRobot);
  request.revoked = true;
  const std::string xml = PermissionsXml(request);
  EXPECT_EQ(xml.find("<allow_rule>"), std::string::npos);
  EXPECT_NE(xml.find("<default>DENY</default>"), std::string::npos);
}

TEST(AccessDocumentsTest, RolesRoundTripByName) {
  for (Role role : {Role::kServer, Role::kRobot, Role::kViewer}) {
    EXPECT_EQ(ParseRole(RoleName(role)), role);
  }
  EXPECT_FALSE(ParseRole("admin").has_value());
}

TEST(AccessDocumentsTest, CommonNameComesFromTheOneLineSubject) {
  EXPECT_EQ(CommonNameOfSubject("/O=fleetmap/OU=robot/CN=robot_7"), "robot_7");
  EXPECT_EQ(CommonNameOfSubject("/CN=alpha/O=fleetmap"), "alpha");
  EXPECT_EQ(CommonNameOfSubject("/O=fleetmap"), "");
}

}  // namespace
}  // namespace fleetmap::security
