// The container image (issue 33, item 6): scripts/build-image.sh builds it with podman from this
// build's Debian package on a debootstrap base (no registry is reached), and a fleet runs from
// it: a server container with its store on a host folder, an agent container exploring a
// simulated office, both on the host's network and a random DDS domain. The server fuses the
// agent's tiles and keeps them in the store; a new server container on the same store restores
// them, which is what compose's named volume relies on. docs/building.md, "Containers".

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap {
namespace {

using ::testing::ContainsRegex;
using ::testing::HasSubstr;

const std::string kBuildDir = FLEETMAP_BINARY_DIR;
const std::string kImage = std::string("localhost/fleetmap:") + FLEETMAP_PROJECT_VERSION;

// podman as build-image.sh left it for this machine (runc, rlimits within the VM's).
std::map<std::string, std::string> PodmanEnvironment() {
  return {{"CONTAINERS_CONF", kBuildDir + "/containers.conf"}};
}

// `podman run` on the host's network (DDS over loopback, as every other test) and `domain`.
std::vector<std::string> RunInImage(int domain, const std::vector<std::string>& volumes,
                                    const std::vector<std::string>& command) {
  std::vector<std::string> argv = {FLEETMAP_PODMAN,
                                   "run",
                                   "--rm",
                                   "--network",
                                   "host",
                                   "--env",
                                   "FLEETMAP_DOMAIN=" + std::to_string(domain)};
  for (const std::string& volume : volumes) argv.insert(argv.end(), {"--volume", volume});
  argv.push_back(kImage);
  argv.insert(argv.end(), command.begin(), command.end());
  return argv;
}

TEST(ContainerImageTest, TheImageBuildsFromThePackageAndRunsAFleetWhoseStoreOutlivesIt) {
  const process::CommandResult built = process::RunCommand(
      {"/bin/bash", std::string(FLEETMAP_SOURCE_DIR) + "/scripts/build-image.sh", kBuildDir},
      std::chrono::minutes(10));
  ASSERT_EQ(built.exit_code, 0) << built.output();

  // The image's programs are this build's: the same version and commit line.
  const process::CommandResult host_version =
      process::RunCommand({kBuildDir + "/cli/fleetmap", "--version"});
  process::Subprocess image_version(RunInImage(0, {}, {"fleetmap", "--version"}),
                                    PodmanEnvironment());
  ASSERT_EQ(image_version.Wait(std::chrono::minutes(1)), 0) << image_version.Output();
  EXPECT_EQ(image_version.StdOut(), host_version.out);

  const testing::ScratchDir scratch("container_image");
  const std::string store_volume = scratch.Path("store") + ":/var/lib/fleetmap";
  std::filesystem::create_directories(scratch.Path("store"));
  const int domain = process::RandomDomainId();
  const std::vector<std::string> server_command = {
      "fleetmap-server",  "--config",   "/etc/fleetmap/server.yaml",
      "--localhost-only", "--duration", "14"};
  process::Subprocess server(RunInImage(domain, {store_volume}, server_command),
                             PodmanEnvironment());
  ASSERT_TRUE(server.WaitForOutput("serving the fleet", std::chrono::minutes(1)))
      << server.Output();
  process::Subprocess agent(RunInImage(domain, {},
                                       {"fleetmap-agent", "--robot-id", "alpha", "--sim", "office",
                                        "--sim-size", "20", "--localhost-only", "--duration", "6"}),
                            PodmanEnvironment());
  EXPECT_EQ(agent.Wait(std::chrono::minutes(1)), 0) << agent.Output();
  ASSERT_EQ(server.Wait(std::chrono::minutes(1)), 0) << server.Output();
  // The server's summary: alpha left after sending tiles, and the fused map has them.
  EXPECT_THAT(server.Output(), ContainsRegex("alpha +left +[1-9]"));
  EXPECT_THAT(server.Output(), ContainsRegex("fused map: [1-9][0-9]* tiles"));
  // The store is the file /etc/fleetmap/server.yaml names, on the host folder.
  EXPECT_TRUE(std::filesystem::exists(scratch.Path("store/fleet.db")));

  process::Subprocess restarted(
      RunInImage(domain, {store_volume},
                 {"fleetmap-server", "--config", "/etc/fleetmap/server.yaml", "--localhost-only",
                  "--duration", "1"}),
      PodmanEnvironment());
  ASSERT_EQ(restarted.Wait(std::chrono::minutes(1)), 0) << restarted.Output();
  EXPECT_THAT(restarted.Output(), ContainsRegex("restored [1-9][0-9]* robot tiles"));
}

}  // namespace
}  // namespace fleetmap
