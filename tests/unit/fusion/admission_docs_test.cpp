// docs/fleet.md's admission table states the defaults of AdmissionOptions: every field the
// options describe has a row naming it, with the same default.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/fusion/tile_admission.hpp"

namespace fleetmap::fusion {
namespace {

const std::string kFleetDoc = std::string(FLEETMAP_TEST_DATA_DIR) + "/../../docs/fleet.md";

std::vector<std::string> Cells(const std::string& row) {
  std::vector<std::string> cells;
  std::stringstream in(row);
  std::string cell;
  std::getline(in, cell, '|');  // before the first bar
  while (std::getline(in, cell, '|')) {
    const size_t first = cell.find_first_not_of(' ');
    const size_t last = cell.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  return cells;
}

// "30 s", "720 h", "288 MB", "4000000": the value in the unit the code describes (s, bytes).
double Number(const std::string& text) {
  std::size_t used = 0;
  const double value = std::stod(text, &used);
  const std::string unit = text.substr(used);
  if (unit == " h") return value * 3600.0;
  if (unit == " MB") return value * (1 << 20);
  if (unit.empty() || unit == " s") return value;
  ADD_FAILURE() << "unknown unit in \"" << text << "\"";
  return NAN;
}

// The admission table's defaults by option field name (`name` in the option column).
std::map<std::string, std::string> DocumentedDefaults() {
  std::ifstream file(kFleetDoc);
  EXPECT_TRUE(file) << kFleetDoc;
  std::map<std::string, std::string> defaults;
  std::string line;
  bool in_table = false;
  while (std::getline(file, line)) {
    if (line.rfind("| check | refused when | option | default |", 0) == 0) in_table = true;
    if (!in_table) continue;
    if (line.empty() || line[0] != '|') break;
    const std::vector<std::string> cells = Cells(line);
    if (cells.size() < 4 || cells[2].size() < 2 || cells[2][0] != '`') continue;
    const std::string name = cells[2].substr(1, cells[2].find('`', 1) - 1);
    defaults[name] = cells[3];
  }
  return defaults;
}

// Every leaf line "name: value" of the options' description.
std::map<std::string, std::string> DescribedDefaults() {
  OptionsPrinter printer;
  AdmissionOptions().Describe(printer);
  std::map<std::string, std::string> described;
  std::stringstream in(printer.text());
  std::string line;
  while (std::getline(in, line)) {
    const size_t colon = line.find(':');
    if (colon == std::string::npos || colon + 1 >= line.size()) continue;  // a nested header
    const size_t first = line.find_first_not_of(' ');
    described[line.substr(first, colon - first)] = line.substr(colon + 2);
  }
  return described;
}

TEST(AdmissionDocsTest, TheAdmissionTableStatesEveryDefaultOfTheCode) {
  const std::map<std::string, std::string> documented = DocumentedDefaults();
  const std::map<std::string, std::string> described = DescribedDefaults();
  ASSERT_GE(described.size(), 15u);  // the budget's fields are described too
  for (const auto& [name, value] : described) {
    const auto row = documented.find(name);
    if (row == documented.end()) {
      ADD_FAILURE() << "docs/fleet.md's admission table has no row for `" << name << "` (" << value
                    << ")";
      continue;
    }
    const double code = Number(value);
    const double doc = Number(row->second);
    EXPECT_NEAR(doc, code, 1e-9 * std::abs(code))
        << "`" << name << "`: docs/fleet.md says " << row->second << ", the code " << value;
  }
}

TEST(AdmissionDocsTest, TheDefaultBudgetsAdmitAnHonestTileAndDecodeLimitsFollowThem) {
  const AdmissionOptions options;
  ASSERT_TRUE(options.Validate().ok());
  const vector_map::TileDecodeLimits limits = options.DecodeLimits();
  EXPECT_EQ(limits.max_vertices, options.budget.max_vertices_per_tile);
  EXPECT_EQ(limits.max_rings, options.budget.max_rings_per_tile);
  EXPECT_EQ(limits.max_geometry_bytes, 64 + 12 * limits.max_vertices + 4 * limits.max_rings);
  // The global budget holds more than one robot's full budget.
  EXPECT_GT(options.budget.max_memory_bytes, options.budget.max_bytes_per_robot);
}

}  // namespace
}  // namespace fleetmap::fusion
