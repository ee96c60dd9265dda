#include "bench/fleet/security_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "bench/fleet/fleet_sim_report.hpp"
#include "common/core/file_io.hpp"

namespace fleetmap::bench {
namespace {

struct RunFigures {
  std::optional<double> join_median_s;
  std::optional<double> join_max_s;
  std::optional<double> handshake_median_s;
  std::optional<double> handshake_max_s;
  int robots_joined = 0;
  std::optional<uint64_t> loopback_bytes;
  uint64_t payload_bytes = 0;
  std::optional<double> latency_p50_ms;
  std::optional<double> latency_p99_ms;
  size_t latency_samples = 0;
};

RunFigures FiguresOf(const FleetRunResult& run) {
  RunFigures figures;
  std::vector<double> joins;
  for (const auto& [name, robot] : run.robots) {
    if (robot.joined_s) joins.push_back(*robot.joined_s);
  }
  figures.robots_joined = static_cast<int>(joins.size());
  std::vector<double> handshakes;
  for (const auto& [name, robot] : run.robots) {
    if (robot.handshake_s) handshakes.push_back(*robot.handshake_s);
  }
  figures.handshake_median_s = Percentile(handshakes, 50.0);
  if (!handshakes.empty()) {
    figures.handshake_max_s = *std::max_element(handshakes.begin(), handshakes.end());
  }
  figures.join_median_s = Percentile(joins, 50.0);
  if (!joins.empty()) figures.join_max_s = *std::max_element(joins.begin(), joins.end());
  figures.loopback_bytes = run.loopback_bytes;
  figures.payload_bytes = run.total_bytes;
  figures.latency_p50_ms = Percentile(run.latencies_ms, 50.0);
  figures.latency_p99_ms = Percentile(run.latencies_ms, 99.0);
  figures.latency_samples = run.latencies_ms.size();
  return figures;
}

std::string Cell(const std::optional<double>& value, const char* unit) {
  return value ? fmt::format("{:.2f} {}", *value, unit) : std::string("-");
}

std::string Ratio(const std::optional<double>& secured, const std::optional<double>& plain) {
  if (!secured || !plain || *plain <= 0.0) return "-";
  return fmt::format("{:.2f}x", *secured / *plain);
}

std::optional<double> AsDouble(const std::optional<uint64_t>& value) {
  if (!value) return std::nullopt;
  return static_cast<double>(*value);
}

nlohmann::json ToJson(const RunFigures& figures) {
  const auto value = [](const auto& optional) {
    return optional ? nlohmann::json(*optional) : nlohmann::json(nullptr);
  };
  return {{"robots_joined", figures.robots_joined},
          {"join_median_s", value(figures.join_median_s)},
          {"join_max_s", value(figures.join_max_s)},
          {"handshake_median_s", value(figures.handshake_median_s)},
          {"handshake_max_s", value(figures.handshake_max_s)},
          {"loopback_bytes", value(figures.loopback_bytes)},
          {"payload_bytes", figures.payload_bytes},
          {"latency_p50_ms", value(figures.latency_p50_ms)},
          {"latency_p99_ms", value(figures.latency_p99_ms)},
          {"latency_samples", figures.latency_samples}};
}

}  // namespace

StatusOr<std::string> WriteSecurityComparison(const FleetRunResult& secured,
                                              const FleetRunResult& plain, bool isolated,
                                              const std::string& out_dir) {
  const RunFigures s = FiguresOf(secured);
  const RunFigures p = FiguresOf(plain);
  std::string table = fmt::format(
      "DDS Security (PKI-DH, AES-GCM, signed permissions) against the same run without it\n"
      "{:<44} {:>14} {:>14} {:>9}\n",
      "", "secured", "plain", "ratio");
  const auto row = [&](const std::string& label, const std::string& a, const std::string& b,
                       const std::string& ratio) {
    table += fmt::format("{:<44} {:>14} {:>14} {:>9}\n", label, a, b, ratio);
  };
  row("robots joined", std::to_string(s.robots_joined), std::to_string(p.robots_joined), "");
  row("join time per robot, median (start->status)", Cell(s.join_median_s, "s"),
      Cell(p.join_median_s, "s"), Ratio(s.join_median_s, p.join_median_s));
  row("join time per robot, worst", Cell(s.join_max_s, "s"), Cell(p.join_max_s, "s"),
      Ratio(s.join_max_s, p.join_max_s));
  row("handshake with the server, median", Cell(s.handshake_median_s, "s"), "-", "");
  row("handshake with the server, worst", Cell(s.handshake_max_s, "s"), "-", "");
  row(isolated ? "loopback bytes (the run's own netns)" : "loopback bytes (host: all traffic)",
      s.loopback_bytes ? std::to_string(*s.loopback_bytes) : "-",
      p.loopback_bytes ? std::to_string(*p.loopback_bytes) : "-",
      Ratio(AsDouble(s.loopback_bytes), AsDouble(p.loopback_bytes)));
  row("robot payload bytes (tiles, statuses)", std::to_string(s.payload_bytes),
      std::to_string(p.payload_bytes),
      Ratio(static_cast<double>(s.payload_bytes), static_cast<double>(p.payload_bytes)));
  row("tile latency p50", Cell(s.latency_p50_ms, "ms"), Cell(p.latency_p50_ms, "ms"),
      Ratio(s.latency_p50_ms, p.latency_p50_ms));
  row("tile latency p99", Cell(s.latency_p99_ms, "ms"), Cell(p.latency_p99_ms, "ms"),
      Ratio(s.latency_p99_ms, p.latency_p99_ms));
  if (s.join_median_s && p.join_median_s) {
    table += fmt::format("join time added by security (secured - plain, median): {:.2f} s\n",
                         *s.join_median_s - *p.join_median_s);
  }
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  const nlohmann::json json = {
      {"secured", ToJson(s)}, {"plain", ToJson(p)}, {"own_network_namespace", isolated}};
  FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(
      (std::filesystem::path(out_dir) / "security.json").string(), json.dump(2) + "\n"));
  return table;
}

}  // namespace fleetmap::bench
