// Runs the real `fleetmap` binary and checks its output and exit codes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/process/subprocess.hpp"
#include "tests/integration/fleetmap_cli.hpp"

namespace fleetmap::cli {
namespace {

using ::testing::HasSubstr;
using testing::RunFleetmap;

std::string DataPath(const std::string& name) {
  return std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/" + name;
}

TEST(CliInfoTest, PrintsJsonSummary) {
  const process::CommandResult run = RunFleetmap({"info", DataPath("trinary_4x3.yaml"), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  const nlohmann::json json = nlohmann::json::parse(run.out);
  EXPECT_EQ(json["file"], DataPath("trinary_4x3.yaml"));
  EXPECT_EQ(json["image"], DataPath("trinary_4x3.pgm"));
  EXPECT_EQ(json["width"], 4);
  EXPECT_EQ(json["height"], 3);
  EXPECT_EQ(json["cells"], 12);
  EXPECT_EQ(json["resolution"], 0.5);
  EXPECT_EQ(json["origin"]["x"], -1.0);
  EXPECT_EQ(json["origin"]["y"], 2.0);
  EXPECT_EQ(json["origin"]["yaw"], 0.0);
  EXPECT_EQ(json["bounds"]["min_x"], -1.0);
  EXPECT_EQ(json["bounds"]["max_x"], 1.0);
  EXPECT_EQ(json["bounds"]["min_y"], 2.0);
  EXPECT_EQ(json["bounds"]["max_y"], 3.5);
  // Cells, top row first: 100 100 -1 0 / -1 -1 0 -1 / 0 100 0 100.
  EXPECT_EQ(json["counts"]["occupied"], 4);
  EXPECT_EQ(json["counts"]["free"], 4);
  EXPECT_EQ(json["counts"]["unknown"], 4);
  EXPECT_EQ(json["mode"], "trinary");
  EXPECT_EQ(json["negate"], false);
  EXPECT_EQ(json["occupied_thresh"], 0.65);
  EXPECT_EQ(json["free_thresh"], 0.196);
}

TEST(CliInfoTest, PrintsTextSummary) {
  const process::CommandResult run = RunFleetmap({"info", DataPath("raw_4x3.yaml")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("size:       4 x 3 cells (12)"));
  EXPECT_THAT(run.out, HasSubstr("resolution: 0.5 m/cell"));
  EXPECT_THAT(run.out, HasSubstr("origin:     x -1 m, y 2 m, yaw 0 rad"));
  EXPECT_THAT(run.out, HasSubstr("bounds:     x [-1, 1] m, y [2, 3.5] m"));
  EXPECT_THAT(run.out, HasSubstr("mode:       raw"));
  EXPECT_THAT(run.out, HasSubstr("negate:     1"));
  EXPECT_THAT(run.out, HasSubstr("thresholds: occupied 0.65, free 0.196"));
  // Raw values 0 1 50 100 / -1 -1 -1 99 / 37 3 100 0 against 0.65 / 0.196: occupied 100, 100, 99;
  // free 0, 1, 3, 0; 50 and 37 in between.
  EXPECT_THAT(run.out, HasSubstr("occupied:   3 (25.0%)"));
  EXPECT_THAT(run.out, HasSubstr("free:       4 (33.3%)"));
  EXPECT_THAT(run.out, HasSubstr("unknown:    5 (41.7%)"));
}

TEST(CliInfoTest, BadInputsExitWithCode2AndNameTheFile) {
  struct Case {
    std::string yaml;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"no_such.yaml", DataPath("no_such.yaml") + ": no such file"},
      {"missing_image.yaml", DataPath("does_not_exist.pgm") + ": no such file"},
      {"syntax_error.yaml", DataPath("syntax_error.yaml") + ": YAML syntax error"},
      {"no_resolution.yaml", "missing required key 'resolution'"},
      {"zero_resolution.yaml", "resolution must be > 0"},
      {"unknown_mode.yaml", "unknown mode 'ternary'"},
      {"escaping_path.yaml", "is outside the YAML's directory"},
      {"bad_magic.yaml", DataPath("bad_magic.pgm") + ": not a PGM file"},
      {"truncated.yaml", DataPath("truncated.pgm") + ": truncated: expected 12 bytes of pixels"},
      {"size_mismatch.yaml", DataPath("size_mismatch.pgm") + ": truncated"},
      {"absurd_size.yaml", DataPath("absurd_size.pgm") + ": image is 100000 x 100000"},
  };
  for (const Case& c : cases) {
    for (const bool json : {false, true}) {
      std::vector<std::string> args = {"info", DataPath(c.yaml)};
      if (json) args.push_back("--json");
      const process::CommandResult run = RunFleetmap(args);
      EXPECT_EQ(run.exit_code, 2) << c.yaml;
      EXPECT_EQ(run.out, "") << c.yaml;
      EXPECT_THAT(run.err, HasSubstr(c.message)) << c.yaml;
    }
  }
}

TEST(CliInfoTest, OptionsReachTheLoader) {
  process::CommandResult run =
      RunFleetmap({"info", DataPath("trinary_4x3.yaml"), "--max-cells", "11"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("more than the limit of 11"));
  run = RunFleetmap({"info", DataPath("escaping_path.yaml"), "--allow-outside-dir"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("trinary_4x3.pgm: no such file"));
}

TEST(CliInfoTest, UsageErrorsExitNonZero) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{}, {"info"}, {"nonsense"}, {"info", "--bogus"}}) {
    const process::CommandResult run = RunFleetmap(args);
    EXPECT_NE(run.exit_code, 0) << ::testing::PrintToString(args);
    EXPECT_NE(run.err, "") << ::testing::PrintToString(args);
  }
  const process::CommandResult help = RunFleetmap({"--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, HasSubstr("info"));
}

TEST(CliInfoTest, EverySharedMapHasInfo) {
  const std::filesystem::path maps_dir(FLEETMAP_SHARED_MAPS_DIR);
  if (!std::filesystem::is_directory(maps_dir)) GTEST_SKIP() << "no shared maps";
  for (const auto& entry : std::filesystem::directory_iterator(maps_dir)) {
    if (entry.path().extension() != ".yaml") continue;
    const process::CommandResult run = RunFleetmap({"info", entry.path().string(), "--json"});
    ASSERT_EQ(run.exit_code, 0) << entry.path() << ": " << run.err;
    const nlohmann::json json = nlohmann::json::parse(run.out);
    const int64_t cells = json["cells"];
    EXPECT_EQ(cells, json["width"].get<int64_t>() * json["height"].get<int64_t>());
    EXPECT_EQ(json["counts"]["occupied"].get<int64_t>() + json["counts"]["free"].get<int64_t>() +
                  json["counts"]["unknown"].get<int64_t>(),
              cells);
    EXPECT_GT(json["counts"]["occupied"].get<int64_t>(), 0) << entry.path();
  }
}

}  // namespace
}  // namespace fleetmap::cli
