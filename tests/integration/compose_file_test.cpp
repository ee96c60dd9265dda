// docker/compose.yaml, checked without a container engine (none runs on the test machines):
// every service runs one of the image's programs with options that program accepts, on one DDS
// domain; the server's store lies on a named volume; the view listens on all addresses at the
// port it publishes; every agent's map is under its read-only maps mount.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"

namespace fleetmap {
namespace {

using ::testing::HasSubstr;

const std::map<std::string, std::string>& Programs() {
  static const std::map<std::string, std::string> programs = {
      {"fleetmap-server", std::string(FLEETMAP_BINARY_DIR) + "/server/fleetmap-server"},
      {"fleetmap-agent", std::string(FLEETMAP_BINARY_DIR) + "/robot_agent/fleetmap-agent"},
      {"fleetmap", std::string(FLEETMAP_BINARY_DIR) + "/cli/fleetmap"}};
  return programs;
}

std::string ValueAfter(const std::vector<std::string>& command, const std::string& flag) {
  for (size_t i = 0; i + 1 < command.size(); ++i) {
    if (command[i] == flag) return command[i + 1];
  }
  return "";
}

TEST(ComposeFileTest, EveryServiceRunsAProgramOfTheImageAsTheFleetNeedsIt) {
  const YAML::Node compose =
      YAML::LoadFile(std::string(FLEETMAP_SOURCE_DIR) + "/docker/compose.yaml");
  const YAML::Node services = compose["services"];
  ASSERT_TRUE(services.IsMap());
  std::set<std::string> domains;
  int servers = 0, views = 0, agents = 0;
  for (const auto& entry : services) {
    const std::string name = entry.first.as<std::string>();
    SCOPED_TRACE(name);
    const YAML::Node service = entry.second;
    EXPECT_EQ(service["image"].as<std::string>(), "fleetmap");
    const auto command = service["command"].as<std::vector<std::string>>();
    ASSERT_FALSE(command.empty());
    ASSERT_EQ(Programs().count(command[0]), 1u) << command[0] << " is not a program of the image";
    domains.insert(service["environment"]["FLEETMAP_DOMAIN"].as<std::string>());

    // The program takes these options: its --help lists every flag the service passes.
    std::vector<std::string> help_argv = {Programs().at(command[0])};
    if (command[0] == "fleetmap") help_argv.push_back(command.at(1));
    help_argv.push_back("--help");
    const process::CommandResult help = process::RunCommand(help_argv);
    ASSERT_EQ(help.exit_code, 0) << help.output();
    for (const std::string& word : command) {
      if (word.rfind("--", 0) == 0) {
        EXPECT_THAT(help.out, HasSubstr(word + " ")) << word;
      }
    }

    const auto volumes = service["volumes"] ? service["volumes"].as<std::vector<std::string>>()
                                            : std::vector<std::string>{};
    if (command[0] == "fleetmap-server") {
      ++servers;
      const std::string store = ValueAfter(command, "--store");
      ASSERT_FALSE(store.empty()) << "the server keeps no store: the fused map dies with it";
      ASSERT_EQ(volumes.size(), 1u);
      const std::string volume = volumes[0].substr(0, volumes[0].rfind(':'));
      const std::string target = volumes[0].substr(volumes[0].rfind(':') + 1);
      EXPECT_EQ(store.rfind(target + "/", 0), 0u) << store << " is not on the volume " << target;
      EXPECT_TRUE(compose["volumes"][volume].IsDefined()) << volume << " is not a named volume";
    } else if (command[0] == "fleetmap") {
      ASSERT_EQ(command.at(1), "view");
      ++views;
      EXPECT_EQ(ValueAfter(command, "--bind"), "0.0.0.0");
      const std::string port = ValueAfter(command, "--port");
      const auto ports = service["ports"].as<std::vector<std::string>>();
      ASSERT_EQ(ports.size(), 1u);
      EXPECT_EQ(ports[0].substr(ports[0].find(':') + 1), port);
    } else {
      ++agents;
      ASSERT_EQ(volumes.size(), 1u);
      // SOURCE:TARGET:ro, where SOURCE may hold colons of its own (${MAPS:-default}).
      ASSERT_THAT(volumes[0], ::testing::EndsWith(":ro"));
      const std::string mount = volumes[0].substr(0, volumes[0].size() - 3);
      const std::string maps = mount.substr(mount.rfind(':') + 1);
      EXPECT_EQ(ValueAfter(command, "--map").rfind(maps + "/", 0), 0u);
    }
  }
  EXPECT_EQ(servers, 1);
  EXPECT_EQ(views, 1);
  EXPECT_GE(agents, 1);
  EXPECT_EQ(domains.size(), 1u) << "the services are on different DDS domains";
}

}  // namespace
}  // namespace fleetmap
