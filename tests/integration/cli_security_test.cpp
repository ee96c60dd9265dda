// `fleetmap security` as a user runs it, and `fleetmap sim --secure`: the simulated fleet secured,
// compared with the same run without security.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/integration/fleetmap_cli.hpp"

namespace fleetmap {
namespace {

using ::testing::HasSubstr;
using testing::RunFleetmap;

TEST(CliSecurityTest, InitEnrollRevokeAndShow) {
  const std::string dir = testing::FreshTempDir("cli_security") + "/fleet";
  const auto init = RunFleetmap({"security", "init", "--dir", dir});
  ASSERT_EQ(init.exit_code, 0) << init.output();
  EXPECT_THAT(init.out, HasSubstr("ca/ca.key"));
  struct stat key {};
  ASSERT_EQ(::stat((dir + "/ca/ca.key").c_str(), &key), 0);
  EXPECT_EQ(key.st_mode & 0777, 0600u);

  ASSERT_EQ(RunFleetmap({"security", "enroll", "--dir", dir, "--robot", "alpha"}).exit_code, 0);
  ASSERT_EQ(RunFleetmap({"security", "enroll", "--dir", dir, "--viewer", "rviz", "--days", "7"})
                .exit_code,
            0);
  ASSERT_EQ(RunFleetmap({"security", "revoke", "--dir", dir, "--robot", "alpha"}).exit_code, 0);

  const auto shown = RunFleetmap({"security", "show", "--dir", dir, "--json"});
  ASSERT_EQ(shown.exit_code, 0) << shown.output();
  const nlohmann::json listed = nlohmann::json::parse(shown.out);
  std::map<std::string, std::pair<std::string, std::string>> by_name;  // role, state
  for (const nlohmann::json& identity : listed["identities"]) {
    by_name[identity["name"]] = {identity["role"], identity["state"]};
  }
  EXPECT_EQ(by_name["alpha"], std::make_pair(std::string("robot"), std::string("revoked")));
  EXPECT_EQ(by_name["rviz"], std::make_pair(std::string("viewer"), std::string("valid")));
  EXPECT_EQ(by_name["server"], std::make_pair(std::string("server"), std::string("valid")));

  const auto table = RunFleetmap({"security", "show", "--dir", dir});
  EXPECT_THAT(table.out, HasSubstr("rviz"));
  std::filesystem::remove_all(std::filesystem::path(dir).parent_path());
}

TEST(CliSecurityTest, MistakesAreClearErrors) {
  const std::string root = testing::FreshTempDir("cli_security_errors");
  const auto no_ca = RunFleetmap({"security", "enroll", "--dir", root + "/none", "--robot", "a"});
  EXPECT_EQ(no_ca.exit_code, 2);
  EXPECT_THAT(no_ca.err, HasSubstr("fleetmap security init"));

  ASSERT_EQ(RunFleetmap({"security", "init", "--dir", root + "/fleet"}).exit_code, 0);
  const auto again = RunFleetmap({"security", "init", "--dir", root + "/fleet"});
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_THAT(again.err, HasSubstr("already holds a fleet CA"));

  const auto both = RunFleetmap(
      {"security", "enroll", "--dir", root + "/fleet", "--robot", "a", "--viewer", "b"});
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_THAT(both.err, HasSubstr("exactly one of --robot and --viewer"));

  const auto bad_name =
      RunFleetmap({"security", "enroll", "--dir", root + "/fleet", "--robot", "a/../b"});
  EXPECT_EQ(bad_name.exit_code, 2);
  EXPECT_THAT(bad_name.err, HasSubstr("not a valid name"));

  const auto unknown =
      RunFleetmap({"security", "revoke", "--dir", root + "/fleet", "--robot", "z"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("z is not enrolled"));
  std::filesystem::remove_all(root);
}

TEST(CliSecurityTest, SimSecureComparesTheSecuredRunWithThePlainOne) {
  const std::string out = testing::FreshTempDir("cli_sim_secure");
  const auto result =
      RunFleetmap({"sim", "--secure", "--robots", "2", "--terrain", "office", "--size", "10",
                   "--seed", "3", "--duration", "12", "--rate", "40", "--out", out},
                  std::chrono::seconds(300));
  ASSERT_EQ(result.exit_code, 0) << result.output();
  EXPECT_THAT(result.out, HasSubstr("DDS Security"));
  std::ifstream in(out + "/security.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  for (const char* run : {"secured", "plain"}) {
    EXPECT_EQ(report[run]["robots_joined"], 2) << run;
    EXPECT_GT(report[run]["latency_samples"].get<int>(), 0) << run;
    EXPECT_GT(report[run]["payload_bytes"].get<int64_t>(), 0) << run;
  }
  // The secured run's credentials stay with the report.
  EXPECT_TRUE(std::filesystem::exists(out + "/security/identities/robot1/cert.pem"));
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace fleetmap
