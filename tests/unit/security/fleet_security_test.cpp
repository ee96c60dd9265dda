#include "common/security/fleet_security.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/security/security_folder.hpp"
#include "common/security/security_identity.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap::security {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

int ModeOf(const fs::path& path) {
  struct stat info {};
  EXPECT_EQ(::stat(path.c_str(), &info), 0) << path;
  return static_cast<int>(info.st_mode & 0777);
}

class FleetSecurityTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const Status made = InitFleet(dir_, FleetSecurityOptions{});
    ASSERT_TRUE(made.ok()) << made;
  }

  testing::ScratchDir scratch_{"fleet_security"};
  std::string dir_ = scratch_.Path("fleet");
  SecurityFolder folder_{dir_};
};

TEST_F(FleetSecurityTest, InitMakesTheCaTheGovernanceAndAValidServerIdentity) {
  for (const fs::path& file :
       {folder_.ca_cert(), folder_.governance(), folder_.governance_xml(), folder_.crl(),
        folder_.cert("server"), folder_.permissions("server")}) {
    EXPECT_TRUE(fs::is_regular_file(file)) << file;
    EXPECT_EQ(ModeOf(file), 0644) << file;
  }
  EXPECT_EQ(ModeOf(folder_.ca_key()), 0600);
  EXPECT_EQ(ModeOf(folder_.key("server")), 0600);

  const StatusOr<SecurityIdentity> server = LoadIdentity(dir_, "server");
  ASSERT_TRUE(server.ok()) << server.status();
  EXPECT_EQ(server->role, Role::kServer);
  EXPECT_TRUE(fs::path(server->cert).is_absolute());
  EXPECT_GT(server->not_after, std::time(nullptr) + 300 * 86400);
}

TEST_F(FleetSecurityTest, InitRefusesAFolderThatAlreadyHasACa) {
  const Status again = InitFleet(dir_, FleetSecurityOptions{});
  EXPECT_FALSE(again.ok());
  EXPECT_THAT(again.message(), HasSubstr("already holds a fleet CA"));
}

TEST_F(FleetSecurityTest, AnEnrolledRobotLoadsWithItsRole) {
  ASSERT_TRUE(Enroll(dir_, "alpha", Role::kRobot, Validity::FromNow(30)).ok());
  const StatusOr<SecurityIdentity> alpha = LoadIdentity(dir_, "alpha");
  ASSERT_TRUE(alpha.ok()) << alpha.status();
  EXPECT_EQ(alpha->name, "alpha");
  EXPECT_EQ(alpha->role, Role::kRobot);
  std::ifstream permissions(folder_.permissions_xml("alpha"));
  const std::string xml((std::istreambuf_iterator<char>(permissions)), {});
  EXPECT_THAT(xml, HasSubstr("<subject_name>CN=alpha,OU=robot,O=fleetmap</subject_name>"));
}

TEST_F(FleetSecurityTest, EnrollRefusesBadNamesTheServerNameAndDuplicates) {
  EXPECT_FALSE(Enroll(dir_, "no spaces", Role::kRobot, Validity::FromNow(1)).ok());
  EXPECT_FALSE(Enroll(dir_, "../escape", Role::kRobot, Validity::FromNow(1)).ok());
  EXPECT_FALSE(Enroll(dir_, "server", Role::kRobot, Validity::FromNow(1)).ok());
  ASSERT_TRUE(Enroll(dir_, "alpha", Role::kRobot, Validity::FromNow(1)).ok());
  const Status twice = Enroll(dir_, "alpha", Role::kViewer, Validity::FromNow(1));
  EXPECT_FALSE(twice.ok());
  EXPECT_THAT(twice.message(), HasSubstr("already enrolled"));
}

TEST_F(FleetSecurityTest, EnrollInAFolderWithoutCaSaysToInitFirst) {
  const Status enrolled =
      Enroll(scratch_.Path("empty"), "alpha", Role::kRobot, Validity::FromNow(1));
  EXPECT_FALSE(enrolled.ok());
  EXPECT_THAT(enrolled.message(), HasSubstr("security init"));
}

TEST_F(FleetSecurityTest, ARevokedRobotNoLongerLoadsAndCanBeEnrolledAfresh) {
  ASSERT_TRUE(Enroll(dir_, "alpha", Role::kRobot, Validity::FromNow(30)).ok());
  ASSERT_TRUE(Enroll(dir_, "bravo", Role::kRobot, Validity::FromNow(30)).ok());
  const Status revoked = Revoke(dir_, "alpha");
  ASSERT_TRUE(revoked.ok()) << revoked;

  const StatusOr<SecurityIdentity> alpha = LoadIdentity(dir_, "alpha");
  ASSERT_FALSE(alpha.ok());
  EXPECT_THAT(alpha.status().message(), HasSubstr("cert.pem"));
  EXPECT_THAT(alpha.status().message(), HasSubstr("revoked"));
  EXPECT_TRUE(LoadIdentity(dir_, "bravo").ok()) << "only alpha is revoked";
  std::ifstream permissions(folder_.permissions_xml("alpha"));
  const std::string xml((std::istreambuf_iterator<char>(permissions)), {});
  EXPECT_EQ(xml.find("<allow_rule>"), std::string::npos) << "re-signed to allow nothing";

  const StatusOr<std::vector<EnrolledIdentity>> listed = ListIdentities(dir_);
  ASSERT_TRUE(listed.ok()) << listed.status();
  ASSERT_EQ(listed->size(), 3u);  // alpha, bravo, server: by name
  EXPECT_EQ((*listed)[0].name, "alpha");
  EXPECT_TRUE((*listed)[0].revoked);
  EXPECT_FALSE((*listed)[1].revoked);
  EXPECT_EQ((*listed)[2].role, "server");

  ASSERT_TRUE(Enroll(dir_, "alpha", Role::kRobot, Validity::FromNow(30)).ok());
  EXPECT_TRUE(LoadIdentity(dir_, "alpha").ok()) << "a new certificate, not on the list";
}

TEST_F(FleetSecurityTest, AnExpiredCertificateIsAnErrorNamingTheFile) {
  const std::time_t now = std::time(nullptr);
  ASSERT_TRUE(Enroll(dir_, "old", Role::kRobot, Validity{now - 10 * 86400, now - 86400}).ok());
  const StatusOr<SecurityIdentity> old = LoadIdentity(dir_, "old");
  ASSERT_FALSE(old.ok());
  EXPECT_THAT(old.status().message(), HasSubstr(folder_.cert("old").filename().string()));
  EXPECT_THAT(old.status().message(), HasSubstr("expired"));
}

TEST_F(FleetSecurityTest, ACertificateOfAnotherCaIsAnErrorNamingTheFile) {
  const std::string other = scratch_.Path("other");
  ASSERT_TRUE(InitFleet(other, FleetSecurityOptions{}).ok());
  ASSERT_TRUE(Enroll(other, "alpha", Role::kRobot, Validity::FromNow(1)).ok());
  // alpha's files from the other fleet, copied into this one.
  fs::copy(SecurityFolder(other).identity("alpha"), folder_.identity("alpha"),
           fs::copy_options::recursive);
  const StatusOr<SecurityIdentity> alpha = LoadIdentity(dir_, "alpha");
  ASSERT_FALSE(alpha.ok());
  EXPECT_THAT(alpha.status().message(), HasSubstr("cert.pem"));
  EXPECT_THAT(alpha.status().message(), HasSubstr("not issued by the fleet CA"));
}

TEST_F(FleetSecurityTest, TamperedPermissionsAreRefused) {
  ASSERT_TRUE(Enroll(dir_, "alpha", Role::kRobot, Validity::FromNow(1)).ok());
  std::ifstream in(folder_.permissions("alpha"));
  std::string text((std::istreambuf_iterator<char>(in)), {});
  in.close();
  // Widen the partition alpha may write in: the signature no longer matches.
  const size_t at = text.find("<partition>alpha</partition>");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 28, "<partition>*****</partition>");
  std::ofstream(folder_.permissions("alpha")) << text;
  const StatusOr<SecurityIdentity> alpha = LoadIdentity(dir_, "alpha");
  ASSERT_FALSE(alpha.ok());
  EXPECT_THAT(alpha.status().message(), HasSubstr("permissions.p7s"));
  EXPECT_THAT(alpha.status().message(), HasSubstr("not signed by the fleet CA"));
}

TEST_F(FleetSecurityTest, MissingFilesAndLooseKeysAreNamed) {
  ASSERT_TRUE(Enroll(dir_, "alpha", Role::kRobot, Validity::FromNow(1)).ok());
  const StatusOr<SecurityIdentity> nobody = LoadIdentity(dir_, "nobody");
  ASSERT_FALSE(nobody.ok());
  EXPECT_THAT(nobody.status().message(), HasSubstr("not enrolled"));

  fs::permissions(folder_.key("alpha"), fs::perms::group_read | fs::perms::others_read,
                  fs::perm_options::add);
  StatusOr<SecurityIdentity> loose = LoadIdentity(dir_, "alpha");
  ASSERT_FALSE(loose.ok());
  EXPECT_THAT(loose.status().message(), HasSubstr("key.pem"));
  EXPECT_THAT(loose.status().message(), HasSubstr("0600"));

  fs::remove(folder_.crl());
  const StatusOr<SecurityIdentity> no_crl = LoadIdentity(dir_, "server");
  ASSERT_FALSE(no_crl.ok());
  EXPECT_THAT(no_crl.status().message(), HasSubstr("crl.pem"));
  EXPECT_THAT(no_crl.status().message(), HasSubstr("missing"));
}

}  // namespace
}  // namespace fleetmap::security
