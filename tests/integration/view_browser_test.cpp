// The web view in a real browser (Debian's chromium, headless): what a person watching the page
// would see of a live fleet. As many robots as live agents, as many drawn tiles as fused tiles
// published, a killed agent shown lost, a prediction's colour once it is confirmed, the serving
// server named and, once it is killed, "no fleet server". The page is
// saved as a screenshot in <build>/test-artifacts/view.png.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <thread>

#include "common/core/wake_up.hpp"
#include "common/scene/submap_node.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "tests/integration/view_fleet.hpp"
#include "tests/support/headless_chromium.hpp"

namespace fleetmap {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using Clock = std::chrono::steady_clock;

// Bounds waits on a loaded 2-core CI machine; not an assertion about speed.
constexpr seconds kDeadline{90};

// What the page's expression gives, or null when it cannot be evaluated.
nlohmann::json Shown(testing::HeadlessChromium& page, const std::string& expression) {
  auto value = page.Evaluate(expression);
  return value.ok() ? *value : nlohmann::json(nullptr);
}

// A predicted door sub-map, 2 x 1.5 m of free cells at (x, y) in the fleet frame.
transport::SubmapMessage DoorPrediction(uint32_t id, scene::SubmapState state, float precision) {
  transport::SubmapMessage node;
  node.submap.id = id;
  node.submap.kind = scene::SubmapKind::kPredictedDoor;
  node.submap.place = 100 + id;
  node.submap.map_from_submap = Pose2{1.0, 1.0, 0.0};
  node.submap.navigable = grid::OccupancyGrid(40, 30, 0.05);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) node.submap.navigable.at(x, y) = grid::kFreeValue;
  }
  node.state = state;
  node.precision = precision;
  node.source_robot = RobotId{"alpha"};
  node.stamp = fleetmap::Clock::now();
  return node;
}

TEST(ViewBrowserTest, ShowsTheLiveFleetAsAPersonWouldSeeIt) {
  const int domain = process::RandomDomainId();
  testing::LiveFleet fleet(domain, {"alpha", "bravo"});
  testing::ViewProcess view(domain);
  ASSERT_GT(view.port(), 0) << view.process().Output();

  // The test's own reader of the fused tiles, to count what the server published.
  auto participant = testing::LoopbackParticipant(domain);
  ASSERT_TRUE(participant.ok()) << participant.status();
  auto wake_up = std::make_shared<WakeUp>();
  auto fused =
      transport::VectorTileReader::Create(**participant, transport::kFusedTilesTopic, wake_up);
  ASSERT_TRUE(fused.ok()) << fused.status();
  auto submaps = transport::SubmapWriter::Create(**participant);
  ASSERT_TRUE(submaps.ok()) << submaps.status();

  auto browser = testing::HeadlessChromium::Open(view.url());
  ASSERT_TRUE(browser.ok()) << browser.status();
  testing::HeadlessChromium& page = **browser;

  // Two live agents: two robot rows, both live.
  auto shown = page.WaitFor(
      "document.querySelectorAll('#robots tbody tr[data-state=\"live\"]').length === 2", kDeadline);
  ASSERT_TRUE(shown.ok()) << shown.status();
  EXPECT_EQ(*shown, true) << fleet.server().Output();

  // The fused tiles published, once the map has stopped changing, are the tiles drawn.
  std::set<std::pair<int, int>> published;
  auto last_change = Clock::now();
  const auto deadline = last_change + kDeadline;
  while (Clock::now() < deadline &&
         (published.empty() || Clock::now() - last_change < seconds(3))) {
    wake_up->WaitFor(milliseconds(100));
    for (const transport::TileEvent& event : (*fused)->Drain()) {
      const std::pair<int, int> key{event.tile.tile.x, event.tile.tile.y};
      if (event.kind == transport::TileEvent::Kind::kTile && published.insert(key).second) {
        last_change = Clock::now();
      }
      if (event.kind == transport::TileEvent::Kind::kRemoved && published.erase(key) > 0) {
        last_change = Clock::now();
      }
    }
  }
  ASSERT_FALSE(published.empty());
  const std::string tiles_drawn = "Number(document.getElementById('map').dataset.drawnTiles) === " +
                                  std::to_string(published.size());
  auto drawn = page.WaitFor(tiles_drawn, kDeadline);
  ASSERT_TRUE(drawn.ok()) << drawn.status();
  EXPECT_EQ(*drawn, true) << "drawn: "
                          << Shown(page, "document.getElementById('map').dataset.drawnTiles")
                          << ", published: " << published.size();
  // The status line says the same, as text.
  EXPECT_EQ(Shown(page, "document.getElementById('status-tiles').textContent"),
            std::to_string(published.size()));

  // A prediction appears orange, then turns green with its precision once confirmed.
  ASSERT_TRUE((*submaps)->Write(DoorPrediction(7, scene::SubmapState::kPredicted, -1.0F)).ok());
  const std::string row = "document.querySelector('#predictions tr[data-submap=\"7\"]')";
  auto predicted = page.WaitFor(row + "?.dataset.state === 'predicted'", kDeadline);
  ASSERT_TRUE(predicted.ok()) << predicted.status();
  EXPECT_EQ(*predicted, true);
  EXPECT_EQ(Shown(page, row + ".dataset.color"), "#f0a030");
  ASSERT_TRUE((*submaps)->Write(DoorPrediction(7, scene::SubmapState::kConfirmed, 0.97F)).ok());
  auto confirmed = page.WaitFor(row + "?.dataset.state === 'confirmed'", kDeadline);
  ASSERT_TRUE(confirmed.ok()) << confirmed.status();
  EXPECT_EQ(*confirmed, true);
  EXPECT_EQ(Shown(page, row + ".dataset.color"), "#2e9e4f");
  EXPECT_EQ(Shown(page, row + ".cells[3].textContent"), "0.970");

  // The page as it looks now, for a person to check.
  const std::string artifacts = std::string(FLEETMAP_BINARY_DIR) + "/test-artifacts";
  std::filesystem::create_directories(artifacts);
  EXPECT_TRUE(page.Screenshot(artifacts + "/view.png").ok());
  EXPECT_GT(std::filesystem::file_size(artifacts + "/view.png"), 10000u);

  // A killed agent is shown lost: DDS declares it when its 2 s liveliness lease lapses.
  fleet.agent("bravo").Signal(SIGKILL);
  const auto killed = Clock::now();
  auto lost = page.WaitFor(
      "document.querySelector('#robots tr[data-robot=\"bravo\"]')?.dataset.state === 'lost'",
      seconds(30));
  const double lost_after = std::chrono::duration<double>(Clock::now() - killed).count();
  ASSERT_TRUE(lost.ok()) << lost.status();
  EXPECT_EQ(*lost, true);
  std::cout << "bravo shown lost " << lost_after << " s after it was killed\n";
  EXPECT_EQ(Shown(page, "document.querySelector('#robots tr[data-robot=\"alpha\"]').dataset.state"),
            "live");
  EXPECT_EQ(Shown(page, "document.getElementById('status-lost').textContent"), "1");

  // The status line names the server that serves; killed, the page says there is none, and the
  // robot that still sends its status is stale: nothing fuses what it sends (docs/standby.md).
  const std::string server_state = "document.getElementById('status-server').dataset.state";
  auto serving = page.WaitFor(server_state + " === 'serving'", kDeadline);
  ASSERT_TRUE(serving.ok()) << serving.status();
  EXPECT_EQ(*serving, true);
  EXPECT_THAT(Shown(page, "document.getElementById('status-server').textContent").dump(),
              ::testing::HasSubstr("server "));
  fleet.server().Signal(SIGKILL);
  auto none = page.WaitFor(server_state + " === 'none'", seconds(30));
  ASSERT_TRUE(none.ok()) << none.status();
  EXPECT_EQ(*none, true);
  EXPECT_EQ(Shown(page, "document.getElementById('status-server').textContent"), "no fleet server");
  auto stale = page.WaitFor(
      "document.querySelector('#robots tr[data-robot=\"alpha\"]')?.dataset.state === 'stale'",
      seconds(30));
  ASSERT_TRUE(stale.ok()) << stale.status();
  EXPECT_EQ(*stale, true);

  submaps->reset();
  fused->reset();
  participant->reset();
}

}  // namespace
}  // namespace fleetmap
