#include "common/core/options_printer.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <string>

namespace fleetmap {
namespace {

struct LeafOptions {
  double resolution = 0.05;
  int retries = 3;
  bool enabled = true;
  std::string path;

  void Describe(OptionsPrinter& out) const {
    out.Add("resolution", resolution);
    out.Add("retries", retries);
    out.Add("enabled", enabled);
    out.Add("path", path);
  }
};

struct RootOptions {
  std::chrono::milliseconds period{1500};
  std::optional<double> limit;
  LeafOptions leaf;

  void Describe(OptionsPrinter& out) const {
    out.Add("period", period);
    out.Add("limit", limit);
    out.Nested("leaf", leaf);
  }
};

TEST(OptionsPrinterTest, PrintsEveryFieldIndentedUnderItsParent) {
  RootOptions options;
  options.leaf.path = "/var/lib/fleetmap.db";
  EXPECT_EQ(DescribeOptions(options),
            "period: 1.5 s\n"
            "limit: none\n"
            "leaf:\n"
            "  resolution: 0.05\n"
            "  retries: 3\n"
            "  enabled: true\n"
            "  path: /var/lib/fleetmap.db\n");
}

TEST(OptionsPrinterTest, ShowsEmptyStringsAndSetOptionals) {
  RootOptions options;
  options.limit = 2.5;
  const std::string text = DescribeOptions(options);
  EXPECT_NE(text.find("limit: 2.5\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  path: \"\"\n"), std::string::npos) << text;
}

}  // namespace
}  // namespace fleetmap
