#include "bench/fleet/bench_flood_command.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <memory>
#include <string_view>
#include <thread>
#include <vector>

#include "bench/fleet/hostile_flood.hpp"
#include "bench/report/bench_command.hpp"
#include "cli/inputs/exit_codes.hpp"

namespace fleetmap::bench {
namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int /*signal*/) { g_stop = true; }

struct BenchFloodArgs {
  HostileFloodOptions flood;
  int participants = 1;
  int domain = -1;  // -1: $FLEETMAP_DOMAIN, else 0
  double duration_s = 0.0;
};

int RunBenchFlood(const BenchFloodArgs& args) {
  if (!IsValidRobotName(args.flood.robot)) {
    std::cerr << "fleetmap bench flood: --robot \"" << args.flood.robot
              << "\" is not a robot name ([A-Za-z][A-Za-z0-9_]*, at most 64 characters)\n";
    return cli::kExitBadInput;
  }
  transport::ParticipantOptions dds;  // loopback only when FLEETMAP_LOCALHOST_ONLY=1
  if (args.domain >= 0) dds.domain_id = args.domain;
  std::vector<std::unique_ptr<HostileFlood>> floods;
  for (int p = 0; p < args.participants; ++p) {
    HostileFloodOptions flood = args.flood;
    if (args.participants > 1) {
      flood.robot += std::to_string(p);
      flood.first_tile_x += 200 * p;  // each participant's keys apart from the others'
    }
    StatusOr<std::unique_ptr<HostileFlood>> created = HostileFlood::Create(dds, flood);
    if (!created.ok()) {
      std::cerr << "fleetmap bench flood: " << created.status().message() << "\n";
      return cli::kExitBadInput;
    }
    floods.push_back(std::move(created).value());
  }
  g_stop = false;
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  for (auto& flood : floods) flood->Start();
  std::cout << fmt::format(
                   "fleetmap bench flood: {} participant(s) flooding rt/fleetmap/robot_tiles, "
                   "each as {} robot id(s) \"{}\"... (Ctrl-C to stop)\n",
                   args.participants, args.flood.ids, args.flood.robot)
            << std::flush;
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(args.duration_s));
  while (!g_stop && (args.duration_s <= 0.0 || std::chrono::steady_clock::now() < until)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  for (auto& flood : floods) flood->RequestStop();  // all at once: each waits for its ids to leave
  uint64_t written = 0;
  for (auto& flood : floods) {
    flood->Stop();
    written += flood->tiles_written();
  }
  std::cout << fmt::format("fleetmap bench flood: {} tiles written\n", written) << std::flush;
  return cli::kExitOk;
}

}  // namespace

uint64_t TilesWrittenByFlood(const std::string& output) {
  constexpr std::string_view kPrefix = "fleetmap bench flood: ";
  constexpr std::string_view kSuffix = " tiles written";
  const size_t end = output.rfind(kSuffix);
  if (end == std::string::npos) return 0;
  const size_t start = output.rfind(kPrefix, end);
  if (start == std::string::npos) return 0;
  const std::string number(output, start + kPrefix.size(), end - start - kPrefix.size());
  return number.find_first_not_of("0123456789") == std::string::npos && !number.empty()
             ? std::stoull(number)
             : 0;
}

void AddBenchFloodCommand(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<BenchFloodArgs>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "flood",
      "Hostile DDS participants flooding a running fleet's server with well-formed tiles "
      "(claims of many robot ids, heavy tiles rewritten, thousands of distinct keys)");
  command->add_option("--domain", args->domain, "DDS domain id (default: $FLEETMAP_DOMAIN, else 0)")
      ->check(CLI::Range(0, 232));
  command->add_option("--participants", args->participants, "hostile DDS participants")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  command->add_option("--ids", args->flood.ids, "robot ids each participant claims")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  command->add_option("--robot", args->flood.robot, "the ids' prefix")->capture_default_str();
  command
      ->add_option("--heavy-tiles", args->flood.heavy_tiles,
                   "tiles of hundreds of short walls, rewritten --rate times a second")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  command->add_option("--rate", args->flood.rate_hz, "heavy-tile rounds a second")
      ->check(CLI::Range(0.1, 1000.0))
      ->capture_default_str();
  command
      ->add_option("--keys", args->flood.distinct_keys,
                   "distinct tile keys written once, spread over the ids")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  command
      ->add_option("--first-tile-x", args->flood.first_tile_x,
                   "the flood's tiles start this many tiles east of the fleet origin")
      ->capture_default_str();
  command->add_option("--duration", args->duration_s, "seconds to flood (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  command->callback([args, exit_code] { *exit_code = RunBenchFlood(*args); });
}

}  // namespace fleetmap::bench
