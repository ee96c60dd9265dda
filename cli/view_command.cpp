#include "cli/view_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <iostream>
#include <memory>
#include <thread>

#include "cli/inputs/exit_codes.hpp"
#include "view/fleet_view.hpp"
#include "view/static_folder.hpp"

namespace fleetmap::cli {
namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int /*signal*/) { g_stop = true; }

constexpr char kDescription[] = R"(
Open the printed address in a browser. The page draws the fused vector tiles (obstacles at their
widths, free space, unknown grey), the fused grid as an optional layer, every robot (pose, path,
live / stale / lost, map revision, wire bytes/s, updates/s, latency), the predicted sub-maps by state
and the learned objects; a table lists the robots and a status line the fleet. Only GET requests are
served and nothing reaches DDS. Binds to 127.0.0.1 unless --bind says otherwise.)";

}  // namespace

int RunView(const ViewOptions& options, std::ostream& out, std::ostream& err) {
  const auto fail = [&](const Status& status) {
    err << "fleetmap view: " << status.message() << "\n";
    return kExitBadInput;
  };
  view::FleetViewOptions view_options;
  view_options.bind = options.bind;
  view_options.port = options.port;
  view_options.max_clients = options.max_clients;
  auto static_dir = view::FindStaticFolder(options.static_dir);
  if (!static_dir.ok()) return fail(static_dir.status());
  view_options.static_dir = *static_dir;
  auto dds = options.fleet.Participant("fleetmap-view");
  if (!dds.ok()) return fail(dds.status());
  view_options.dds = *std::move(dds);
  auto view = view::FleetView::Start(std::move(view_options));
  if (!view.ok()) return fail(view.status());
  out << fmt::format("fleetmap view: open {} (DDS domain {}; Ctrl-C to stop)\n", (*view)->url(),
                     (*view)->domain_id())
      << std::flush;

  g_stop = false;
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  const auto start = std::chrono::steady_clock::now();
  const auto until = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(options.duration_s));
  while (!g_stop && (options.duration_s <= 0.0 || std::chrono::steady_clock::now() < until)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const view::BroadcastCounters counters = (*view)->counters();
  const view::ViewTraffic traffic = (*view)->traffic();
  view->reset();  // the web server, then the participant, before the process ends
  out << fmt::format(
      "fleetmap view: stopped; {} browsers served ({} bytes sent, gzip), {} refused (more than "
      "{} at once), {} resyncs\n",
      counters.connected, traffic.bytes_to_browsers, counters.refused, options.max_clients,
      counters.resyncs);
  const double seconds = std::max(traffic.seconds, 1e-3);
  out << fmt::format(
      "fleetmap view: per browser, {} deltas, {} bytes of JSON in {:.0f} s ({:.0f} B/s; whole "
      "state now "
      "{} bytes); the fused grid as PNG at each of its {} updates: {} bytes ({:.0f} B/s, {})\n",
      traffic.deltas, traffic.delta_bytes, seconds, traffic.delta_bytes / seconds,
      traffic.last_full_bytes, traffic.grids, traffic.grid_png_bytes,
      traffic.grid_png_bytes / seconds,
      traffic.delta_bytes > 0
          ? fmt::format("{:.1f}x the deltas",
                        static_cast<double>(traffic.grid_png_bytes) / traffic.delta_bytes)
          : std::string("no deltas"));
  return kExitOk;
}

std::shared_ptr<config::ConfigurableCommand> AddViewCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* command =
      app.add_subcommand("view", "Serve a live web view of the fleet (map, robots, predictions)");
  command->footer(kDescription);
  command->add_option("--port", options->port, "TCP port (0: any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  command->add_option("--bind", options->bind, "address to listen on")->capture_default_str();
  command->add_option("--max-clients", options->max_clients, "browsers served at once")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_option("--duration", options->duration_s, "stop after this many seconds (0: never)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--static-dir", options->static_dir,
                      "the page's folder (default: the installed one, or $FLEETMAP_VIEW_DIR)");
  auto fleet = std::make_shared<FleetReaderFlags>(command, &options->fleet);
  auto config = std::make_shared<config::ConfigurableCommand>(
      command, "fleetmap view", "fleetmap_view", config::DdsEnvironment());
  command->callback([options, fleet, config, exit_code] {
    if (config->print_requested()) {
      config->Print(std::cout);
      *exit_code = kExitOk;
      return;
    }
    fleet->ApplyDomain();
    *exit_code = RunView(*options, std::cout, std::cerr);
  });
  return config;
}

}  // namespace fleetmap::cli
