// The web view in a real browser (Debian's chromium, headless): what a person watching the page
// would see of a live fleet, read from the page's DOM and from the pixels it drew. As many robots
// as live agents, each in its own colour; a legend for the four robot states; as many drawn tiles
// as fused tiles published, with no seam where two tiles meet at any zoom; a prediction's colour
// once it is confirmed; no robot shown live while the page has lost its view process; a killed
// agent shown lost and a cleanly stopped one left; the serving server named and, once it is
// killed, "no fleet server". The page is saved as a screenshot in <build>/test-artifacts/view.png.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "common/core/wake_up.hpp"
#include "common/extrapolation/entities_json.hpp"
#include "common/grid/map_io.hpp"
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

// The same, as text ("" when it is not a string).
std::string ShownText(testing::HeadlessChromium& page, const std::string& expression) {
  const nlohmann::json value = Shown(page, expression);
  return value.is_string() ? value.get<std::string>() : "";
}

std::string RowOf(const std::string& robot) {
  return "document.querySelector('#robots tr[data-robot=\"" + robot + "\"]')";
}

// How far apart two '#rrggbb' colours are: the largest difference of a channel.
int ColourDistance(const std::string& a, const std::string& b) {
  if (a.size() != 7 || b.size() != 7) return 255;
  int largest = 0;
  for (size_t i = 1; i < 7; i += 2) {
    const int difference =
        std::abs(std::stoi(a.substr(i, 2), nullptr, 16) - std::stoi(b.substr(i, 2), nullptr, 16));
    largest = std::max(largest, difference);
  }
  return largest;
}

// The colour ('#rrggbb') of the pixel at the centre of a robot's dot, as the robots' canvas holds
// it.
std::string DotPixel(testing::HeadlessChromium& page, const std::string& robot) {
  return ShownText(page, R"((() => {
    const canvas = document.querySelector('.leaflet-robots-pane canvas');
    const box = canvas.getBoundingClientRect();
    const mapBox = document.getElementById('map').getBoundingClientRect();
    const robot = state.robots[')" +
                             robot + R"('];
    const at = map.latLngToContainerPoint([robot.y, robot.x]);
    const scale = canvas.width / box.width;
    const x = Math.round((mapBox.left + at.x - box.left) * scale);
    const y = Math.round((mapBox.top + at.y - box.top) * scale);
    const [r, g, b] = canvas.getContext('2d').getImageData(x, y, 1, 1).data;
    return '#' + [r, g, b].map((v) => v.toString(16).padStart(2, '0')).join('');
  })())");
}

// Centres the map on the tile corner nearest the middle of the drawn tiles that has the most
// drawn tiles around it, at `zoom`; returns that corner [x, y] in metres.
nlohmann::json CentreOnATileCorner(testing::HeadlessChromium& page, double zoom) {
  return Shown(page, R"((() => {
    const keys = new Set(Object.keys(drawn.tiles));
    const any = Object.values(drawn.tiles)[0];
    const size = any.bounds[1][1] - any.bounds[0][1];
    const tiles = [...keys].map((key) => key.split(',').map(Number));
    const middle = tiles.reduce(([sx, sy], [x, y]) => [sx + x + 0.5, sy + y + 0.5], [0, 0])
      .map((sum) => sum / tiles.length);
    let best = null;
    tiles.forEach(([x, y]) => [[x, y], [x + 1, y], [x, y + 1], [x + 1, y + 1]].forEach(([cx, cy]) => {
      const around = [[cx - 1, cy - 1], [cx, cy - 1], [cx - 1, cy], [cx, cy]]
        .filter(([tx, ty]) => keys.has(`${tx},${ty}`)).length;
      const distance = Math.hypot(cx - middle[0], cy - middle[1]);
      if (!best || around > best.around || (around === best.around && distance < best.distance)) {
        best = { cx, cy, around, distance };
      }
    }));
    map.setView([best.cy * size, best.cx * size], )" +
                         std::to_string(zoom) + R"(, { animate: false });
    return [best.cx * size, best.cy * size];
  })())");
}

// Scans the free-space canvas across the tile borders through the corner the map is centred on
// (CentreOnATileCorner): every row across the vertical border and every column across the
// horizontal one, where the pixels a little way either side are opaque white (free space on both
// sides). {crossings, seams}: how many such were found, and how many of them had a pixel between
// that was not opaque white (the unknown grey showing through).
nlohmann::json SeamsAtTheCentre(testing::HeadlessChromium& page) {
  return Shown(page, R"((() => {
    const canvas = document.querySelector('.leaflet-free-pane canvas');
    const box = canvas.getBoundingClientRect();
    const mapBox = document.getElementById('map').getBoundingClientRect();
    const scale = canvas.width / box.width;
    const pixels = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    const white = (x, y) => {
      if (x < 0 || y < 0 || x >= canvas.width || y >= canvas.height) return false;
      const i = 4 * (y * canvas.width + x);
      return pixels[i] >= 250 && pixels[i + 1] >= 250 && pixels[i + 2] >= 250 && pixels[i + 3] >= 250;
    };
    const centre = map.getSize().divideBy(2);
    const cx = (mapBox.left + centre.x - box.left) * scale;
    const cy = (mapBox.top + centre.y - box.top) * scale;
    // Past where the old drawing left its gap (one cell), plus a margin.
    const reach = Math.ceil(0.05 * Math.pow(2, map.getZoom()) * scale) + 3;
    let crossings = 0;
    let seams = 0;
    const across = (at) => {  // at(offset): the pixel `offset` from the border
      if (!at(-reach) || !at(reach)) return;
      ++crossings;
      for (let d = -reach + 1; d < reach; ++d) {
        if (!at(d)) { ++seams; return; }
      }
    };
    for (let y = 0; y < canvas.height; ++y) across((d) => white(Math.round(cx) + d, y));
    for (let x = 0; x < canvas.width; ++x) across((d) => white(x, Math.round(cy) + d));
    return { crossings, seams };
  })())");
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
  const std::string two_live =
      "document.querySelectorAll('#robots tbody tr[data-state=\"live\"]').length === 2";
  auto shown = page.WaitFor(two_live, kDeadline);
  ASSERT_TRUE(shown.ok()) << shown.status();
  EXPECT_EQ(*shown, true) << fleet.server().Output();

  // The legend names the four states a robot can be shown in.
  EXPECT_EQ(Shown(page,
                  "[...document.querySelectorAll('#legend li[data-state]')]"
                  ".map((item) => item.dataset.state).join(' ')"),
            "live stale lost left");

  // Each robot has its own colour: its row says which, its path is drawn in it, and so is its dot.
  const std::string alpha_colour = ShownText(page, RowOf("alpha") + ".dataset.color");
  const std::string bravo_colour = ShownText(page, RowOf("bravo") + ".dataset.color");
  EXPECT_GT(ColourDistance(alpha_colour, bravo_colour), 60) << alpha_colour << " " << bravo_colour;
  EXPECT_EQ(Shown(page, "drawn.robots.alpha[0].options.color"), alpha_colour);
  EXPECT_EQ(Shown(page, "drawn.robots.bravo[0].options.color"), bravo_colour);
  Shown(page,
        "map.setView([(state.robots.alpha.y + state.robots.bravo.y) / 2,"
        " (state.robots.alpha.x + state.robots.bravo.x) / 2], 4, { animate: false }), true");
  std::this_thread::sleep_for(milliseconds(500));  // the canvases redraw on the next frames
  EXPECT_LE(ColourDistance(DotPixel(page, "alpha"), alpha_colour), 2) << DotPixel(page, "alpha");
  EXPECT_LE(ColourDistance(DotPixel(page, "bravo"), bravo_colour), 2) << DotPixel(page, "bravo");

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

  // Where tiles meet, free space runs on without a seam of the unknown grey, at any zoom.
  for (const double zoom : {3.0, 5.0, 7.0}) {
    const nlohmann::json corner = CentreOnATileCorner(page, zoom);
    std::this_thread::sleep_for(milliseconds(500));
    const nlohmann::json seams = SeamsAtTheCentre(page);
    ASSERT_TRUE(seams.is_object()) << seams;
    EXPECT_GT(seams["crossings"].get<int>(), 20)
        << "zoom " << zoom << ", corner " << corner << ": too few free pixels across its borders";
    EXPECT_EQ(seams["seams"], 0) << "zoom " << zoom << ", corner " << corner << ": " << seams;
  }
  Shown(page, "fitted = false, fitOnce(), true");  // the whole map again, for the screenshot

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

  // A page that lost its view process shows nobody live; it follows the fleet again once a view
  // process answers on its port.
  const int port = view.port();
  view.process().Signal(SIGTERM);
  EXPECT_TRUE(view.process().Wait(seconds(30)).has_value());
  auto unheard = page.WaitFor(
      "document.getElementById('connection').dataset.state === 'reconnecting' && "
      "document.querySelectorAll('#robots tbody tr').length === 2 && "
      "document.querySelectorAll('#robots tbody tr[data-state=\"live\"]').length === 0",
      seconds(30));
  ASSERT_TRUE(unheard.ok()) << unheard.status();
  EXPECT_EQ(*unheard, true);
  EXPECT_EQ(Shown(page, RowOf("alpha") + ".dataset.state"), "stale");
  EXPECT_EQ(Shown(page, "document.getElementById('status-live').textContent"), "0");
  testing::ViewProcess view_again(domain, {}, port);
  ASSERT_EQ(view_again.port(), port) << view_again.process().Output();
  auto followed = page.WaitFor(two_live, kDeadline);
  ASSERT_TRUE(followed.ok()) << followed.status();
  EXPECT_EQ(*followed, true);

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

  // An agent stopped cleanly leaves: it is shown left, not lost, once its process has gone too.
  fleet.agent("alpha").Signal(SIGTERM);
  EXPECT_TRUE(fleet.agent("alpha").Wait(seconds(30)).has_value());
  auto left = page.WaitFor(RowOf("alpha") + "?.dataset.state === 'left'", seconds(30));
  ASSERT_TRUE(left.ok()) << left.status();
  EXPECT_EQ(*left, true) << fleet.agent("alpha").Output();
  std::this_thread::sleep_for(seconds(3));  // past the lease its writer had
  EXPECT_EQ(Shown(page, RowOf("alpha") + ".dataset.state"), "left");
  EXPECT_EQ(Shown(page, RowOf("bravo") + ".dataset.state"), "lost");

  submaps->reset();
  fused->reset();
  participant->reset();
}

// The newest route graph `reader` receives once it satisfies `wanted` and has not changed for 3 s,
// or the last one by the deadline (nothing if none came).
template <typename Wanted>
std::optional<transport::RouteGraphMessage> SettledRouteGraph(transport::RouteGraphReader& reader,
                                                              WakeUp& wake_up, Wanted wanted) {
  std::optional<transport::RouteGraphMessage> newest;
  auto last_change = Clock::now();
  const auto deadline = last_change + kDeadline;
  while (Clock::now() < deadline &&
         (!newest || !wanted(*newest) || Clock::now() - last_change < seconds(3))) {
    wake_up.WaitFor(milliseconds(100));
    for (transport::RouteGraphEvent& event : reader.Drain()) {
      if (event.kind != transport::RouteGraphEvent::Kind::kSample) continue;
      newest = std::move(event.message);
      last_change = Clock::now();
    }
  }
  return newest;
}

// The route graph (docs/route-graph.md) of a live server is drawn as a layer: the page's edges are
// those of the newest revision the server published.
TEST(ViewBrowserTest, DrawsTheServersRouteGraph) {
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  process::Subprocess server(
      {testing::kServerBinary, "--duration", "120", "--route-graph", "--route-graph-radius", "0.2",
       "--no-object-learning", "--no-extrapolation", "--map-period", "0.5"},
      env);
  process::Subprocess agent(
      {testing::kAgentBinary, "--robot-id", "alpha", "--map", testing::kViewTestMap}, env);
  testing::ViewProcess view(domain);
  ASSERT_GT(view.port(), 0) << view.process().Output();
  auto participant = testing::LoopbackParticipant(domain);
  ASSERT_TRUE(participant.ok()) << participant.status();
  auto wake_up = std::make_shared<WakeUp>();
  auto graphs = transport::RouteGraphReader::Create(**participant, wake_up);
  ASSERT_TRUE(graphs.ok()) << graphs.status();
  auto browser = testing::HeadlessChromium::Open(view.url());
  ASSERT_TRUE(browser.ok()) << browser.status();
  testing::HeadlessChromium& page = **browser;

  // The newest revision, once the graph has stopped changing.
  const std::optional<transport::RouteGraphMessage> newest = SettledRouteGraph(
      **graphs, *wake_up, [](const transport::RouteGraphMessage&) { return true; });
  ASSERT_TRUE(newest.has_value()) << server.Output();
  ASSERT_FALSE(newest->graph.edges.empty()) << newest->graph.message;
  const std::string edges_drawn = "Number(document.getElementById('map').dataset.routeEdges) === " +
                                  std::to_string(newest->graph.edges.size());
  auto drawn = page.WaitFor(edges_drawn, kDeadline);
  ASSERT_TRUE(drawn.ok()) << drawn.status();
  EXPECT_EQ(*drawn, true) << "drawn: "
                          << Shown(page, "document.getElementById('map').dataset.routeEdges")
                          << ", published: " << newest->graph.edges.size();
  EXPECT_EQ(Shown(page, "state.routeGraphs.fleet.revision"), newest->revision);
  EXPECT_EQ(Shown(page, "state.routeGraphs.fleet.kinds.length"), newest->graph.nodes.size());
  // One polyline of edges and a dot per node, on the map.
  EXPECT_EQ(Shown(page, "drawn.routes.fleet.length"), newest->graph.nodes.size() + 1);
}

// A room predicted behind a closed door (docs/route-graph.md, *Predicted space*): the page draws
// the edges into it apart from the observed ones, as many as the server marked predicted.
TEST(ViewBrowserTest, DrawsTheRouteGraphsPredictedEdgesApart) {
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  // A 3.8 m room, x in [0, 4), with a closed door in its east wall at y in [1.5, 2.4]; east of
  // it nothing is known.
  const std::string folder = ::testing::TempDir() + "/view_predicted_" + std::to_string(domain);
  std::filesystem::create_directories(folder);
  grid::OccupancyGrid map(160, 80, 0.05, Pose2{}, grid::kUnknownValue);
  for (int y = 0; y < 80; ++y) {
    for (int x = 0; x < 81; ++x) {
      const bool inside = x >= 2 && x < 79 && y >= 2 && y < 78;
      map.at(x, y) = inside ? grid::kFreeValue : grid::kOccupiedValue;
    }
  }
  const std::string map_path = folder + "/room.yaml";
  ASSERT_TRUE(grid::SaveMap(map, map_path).ok());
  scene::Entities entities;
  entities.doors.push_back({"door_east", {4.0, 1.5}, {4.0, 2.4}, {1.0, 0.0}, false});
  const std::string entities_path = folder + "/entities.json";
  std::ofstream(entities_path) << extrapolation::EntitiesToJson(entities);

  process::Subprocess server(
      {testing::kServerBinary, "--duration", "120", "--route-graph", "--route-graph-radius", "0.25",
       "--no-object-learning", "--map-period", "0.5"},
      env);
  process::Subprocess agent({testing::kAgentBinary, "--robot-id", "alpha", "--map", map_path,
                             "--entities", entities_path},
                            env);
  testing::ViewProcess view(domain);
  ASSERT_GT(view.port(), 0) << view.process().Output();
  auto participant = testing::LoopbackParticipant(domain);
  ASSERT_TRUE(participant.ok()) << participant.status();
  auto wake_up = std::make_shared<WakeUp>();
  auto graphs = transport::RouteGraphReader::Create(**participant, wake_up);
  ASSERT_TRUE(graphs.ok()) << graphs.status();
  auto browser = testing::HeadlessChromium::Open(view.url());
  ASSERT_TRUE(browser.ok()) << browser.status();
  testing::HeadlessChromium& page = **browser;

  // The newest revision with predicted edges, once the graph has stopped changing.
  const auto predicted_edges = [](const route_graph::RouteGraph& graph) {
    return std::count_if(graph.edges.begin(), graph.edges.end(),
                         [](const route_graph::RouteEdge& edge) { return edge.predicted; });
  };
  const std::optional<transport::RouteGraphMessage> newest =
      SettledRouteGraph(**graphs, *wake_up, [&](const transport::RouteGraphMessage& message) {
        return predicted_edges(message.graph) > 0;
      });
  ASSERT_TRUE(newest.has_value()) << server.Output();
  const auto predicted = predicted_edges(newest->graph);
  ASSERT_GT(predicted, 0) << server.Output();
  const std::string drawn_all =
      "Number(document.getElementById('map').dataset.routePredictedEdges) === " +
      std::to_string(predicted) +
      " && state.routeGraphs.fleet.revision === " + std::to_string(newest->revision);
  auto drawn = page.WaitFor(drawn_all, kDeadline);
  ASSERT_TRUE(drawn.ok()) << drawn.status();
  EXPECT_EQ(*drawn, true) << "drawn: "
                          << Shown(page,
                                   "document.getElementById('map').dataset.routePredictedEdges")
                          << ", published: " << predicted;
  EXPECT_EQ(Shown(page, "document.getElementById('map').dataset.routeBlockedEdges"), "0");
  // The observed edges as one polyline, each predicted edge a dashed line of its own, a dot per
  // node.
  EXPECT_EQ(Shown(page, "drawn.routes.fleet.length"),
            newest->graph.nodes.size() + 1 + static_cast<size_t>(predicted));
}

// Shards (docs/shards.md): the status line names each shard and its server, and the map outlines
// each shard's region with its name.
TEST(ViewBrowserTest, ShowsEachShardAndItsRegion) {
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  const std::string server = std::string(FLEETMAP_BINARY_DIR) + "/server/fleetmap-server";
  process::Subprocess west(
      {server, "--duration", "120", "--shard", "west", "--region", "0", "0", "30", "20", "--name",
       "west-server", "--no-object-learning", "--no-extrapolation"},
      env);
  process::Subprocess east(
      {server, "--duration", "120", "--shard", "east", "--region", "30", "0", "60", "20", "--name",
       "east-server", "--no-object-learning", "--no-extrapolation"},
      env);
  testing::ViewProcess view(domain);
  ASSERT_GT(view.port(), 0) << view.process().Output();
  auto browser = testing::HeadlessChromium::Open(view.url());
  ASSERT_TRUE(browser.ok()) << browser.status();
  testing::HeadlessChromium& page = **browser;

  const std::string text = "document.getElementById('status-server').textContent";
  auto named = page.WaitFor(text + ".startsWith('2 shards')", kDeadline);
  ASSERT_TRUE(named.ok()) << named.status();
  EXPECT_EQ(*named, true) << Shown(page, text) << west.Output() << east.Output();
  EXPECT_EQ(Shown(page, text), "2 shards: east (server east-server), west (server west-server)");
  EXPECT_EQ(Shown(page, "document.getElementById('status-server').dataset.state"), "serving");
  // An outline and a name per shard, the outline on the shard's region.
  EXPECT_EQ(Shown(page, "shardLayer.getLayers().length"), 4);
  EXPECT_EQ(Shown(page,
                  "[...document.querySelectorAll('.shard-label')].map((l) => l.textContent)"
                  ".sort().join(' ')"),
            "shard east shard west");
  EXPECT_EQ(Shown(page,
                  "(() => { const b = shardLayer.getLayers().find((l) => l.getBounds)"
                  ".getBounds(); return [b.getWest(), b.getSouth(), b.getEast(), b.getNorth()]; "
                  "})()"),
            nlohmann::json::parse("[30, 0, 60, 20]"));
  const std::string artifacts = std::string(FLEETMAP_BINARY_DIR) + "/test-artifacts";
  std::filesystem::create_directories(artifacts);
  EXPECT_TRUE(page.Screenshot(artifacts + "/view_shards.png").ok());
}

}  // namespace
}  // namespace fleetmap
