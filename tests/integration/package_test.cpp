// The Debian package (issue 33, item 6): `cpack` on this build tree makes a .deb that holds the
// three programs, the web view's page, the systemd units and the docs; its Depends name the
// libraries the programs link (dpkg-shlibdeps); the units start the installed programs; and the
// packaged `fleetmap` runs from the unpacked tree.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>

#include "common/process/subprocess.hpp"
#include "tests/scratch_dir.hpp"

namespace fleetmap {
namespace {

using ::testing::HasSubstr;

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(PackageTest, TheDebHoldsTheProgramsThePageAndTheUnitsThatStartThem) {
  const testing::ScratchDir scratch("package");
  const process::CommandResult cpack = process::RunCommand(
      {FLEETMAP_CPACK, "--config", std::string(FLEETMAP_BINARY_DIR) + "/CPackConfig.cmake", "-B",
       scratch.Path("out")},
      std::chrono::minutes(5));
  ASSERT_EQ(cpack.exit_code, 0) << cpack.output();
  std::string deb;
  for (const auto& entry : std::filesystem::directory_iterator(scratch.Path("out"))) {
    if (entry.path().extension() == ".deb") deb = entry.path().string();
  }
  ASSERT_FALSE(deb.empty()) << cpack.output();

  const process::CommandResult listing =
      process::RunCommand({FLEETMAP_DPKG_DEB, "--contents", deb});
  ASSERT_EQ(listing.exit_code, 0) << listing.output();
  for (const char* file :
       {"./usr/bin/fleetmap", "./usr/bin/fleetmap-server", "./usr/bin/fleetmap-agent",
        "./usr/lib/systemd/system/fleetmap-server.service",
        "./usr/lib/systemd/system/fleetmap-agent@.service",
        "./usr/lib/systemd/system/fleetmap-view.service", "./usr/lib/sysctl.d/60-fleetmap.conf",
        "./usr/share/fleetmap/view/index.html", "./usr/share/fleetmap/view/view.js",
        "./usr/share/fleetmap/view/leaflet/leaflet.js", "./usr/share/doc/fleetmap/README.md",
        "./usr/share/doc/fleetmap/docs/topics.md", "./etc/fleetmap/server.yaml",
        "./etc/fleetmap/agent.yaml", "./etc/fleetmap/view.yaml",
        "./usr/share/doc/fleetmap/docs/config/fleet_params.yaml"}) {
    EXPECT_THAT(listing.out, HasSubstr(std::string(file) + "\n")) << file;
  }

  const process::CommandResult depends =
      process::RunCommand({FLEETMAP_DPKG_DEB, "--field", deb, "Depends"});
  ASSERT_EQ(depends.exit_code, 0) << depends.output();
  EXPECT_THAT(depends.out, HasSubstr("libfastrtps2.9"));
  EXPECT_THAT(depends.out, HasSubstr("libsqlite3"));

  // Unpacked, the units start programs the package holds, and the packaged CLI runs.
  const std::string root = scratch.Path("root");
  const process::CommandResult unpack =
      process::RunCommand({FLEETMAP_DPKG_DEB, "--extract", deb, root});
  ASSERT_EQ(unpack.exit_code, 0) << unpack.output();
  for (const auto& [unit, program, config] :
       {std::tuple{"fleetmap-server.service", "/usr/bin/fleetmap-server", "server.yaml"},
        std::tuple{"fleetmap-agent@.service", "/usr/bin/fleetmap-agent", "agent.yaml"},
        std::tuple{"fleetmap-view.service", "/usr/bin/fleetmap", "view.yaml"}}) {
    const std::string text = ReadFile(root + "/usr/lib/systemd/system/" + unit);
    EXPECT_THAT(text, HasSubstr(std::string("ExecStart=") + program + " ")) << unit;
    EXPECT_THAT(text, HasSubstr(std::string("--config /etc/fleetmap/") + config)) << unit;
    EXPECT_TRUE(std::filesystem::exists(root + program)) << program;
    EXPECT_TRUE(std::filesystem::exists(root + "/etc/fleetmap/" + config)) << config;
  }
  // The config files are conffiles: an upgrade keeps what the operator changed.
  const process::CommandResult conffiles =
      process::RunCommand({FLEETMAP_DPKG_DEB, "--info", deb, "conffiles"});
  ASSERT_EQ(conffiles.exit_code, 0) << conffiles.output();
  EXPECT_THAT(conffiles.out, HasSubstr("/etc/fleetmap/server.yaml"));
  const process::CommandResult version =
      process::RunCommand({root + "/usr/bin/fleetmap", "--version"});
  EXPECT_EQ(version.exit_code, 0) << version.output();
  EXPECT_THAT(version.out, HasSubstr("Fast DDS"));
}

}  // namespace
}  // namespace fleetmap
