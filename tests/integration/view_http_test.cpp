// `fleetmap view`'s HTTP side and its event stream, with real processes: what it serves and
// refuses, and the delta protocol (a late browser gets the whole state first, a stalled browser is
// dropped without delaying the others, twenty browsers at once, a bounded number of them).

#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/core/robot_status.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/robot_status_writer.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_writer.hpp"
#include "tests/integration/fleetmap_cli.hpp"
#include "tests/integration/view_fleet.hpp"

// Last: httplib brings <resolv.h>, whose `_res` macro breaks Eigen's headers included above.
#include <httplib.h>

namespace fleetmap {
namespace {

using nlohmann::json;
using std::chrono::milliseconds;
using std::chrono::seconds;
using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

// Bounds waits on a loaded 2-core CI machine; not an assertion about speed.
constexpr seconds kDeadline{90};

// One browser's /events, read on a thread of its own: every event, with the page's own merging
// of deltas into the state (removed items dropped).
class EventStream {
 public:
  explicit EventStream(int port) : client_("127.0.0.1", port) {
    client_.set_read_timeout(seconds(60));
    thread_ = std::thread([this] { Read(); });
  }
  ~EventStream() {
    stop_ = true;
    client_.stop();
    thread_.join();
  }

  int status() const { return status_; }
  size_t event_count() const {
    std::lock_guard lock(mutex_);
    return events_.size();
  }
  json first_event() const {
    std::lock_guard lock(mutex_);
    return events_.empty() ? json() : events_.front();
  }
  // The merged state: {"tiles": {...}, "robots": {...}}.
  json state() const {
    std::lock_guard lock(mutex_);
    return state_;
  }
  // Every x the robot `id` was shown at, in order.
  std::vector<double> xs_of(const std::string& id) const {
    std::lock_guard lock(mutex_);
    auto it = xs_.find(id);
    return it == xs_.end() ? std::vector<double>{} : it->second;
  }
  bool WaitUntil(const std::function<bool(const EventStream&)>& condition) const {
    const auto deadline = Clock::now() + kDeadline;
    while (Clock::now() < deadline) {
      if (condition(*this)) return true;
      std::this_thread::sleep_for(milliseconds(50));
    }
    return false;
  }

 private:
  void Read() {
    std::string pending;
    auto response = client_.Get("/events", [&](const char* data, size_t length) {
      pending.append(data, length);
      for (size_t end; (end = pending.find("\n\n")) != std::string::npos;) {
        const std::string frame = pending.substr(0, end);
        pending.erase(0, end + 2);
        if (frame.rfind("data: ", 0) == 0) Merge(json::parse(frame.substr(6)));
      }
      return !stop_;
    });
    status_ = response ? response->status : -1;
  }

  void Merge(const json& event) {
    std::lock_guard lock(mutex_);
    events_.push_back(event);
    if (event["type"] == "full") state_ = {{"tiles", json::object()}, {"robots", json::object()}};
    for (const char* section : {"tiles", "robots"}) {
      if (!event.contains(section)) continue;
      for (const auto& [key, item] : event[section].items()) {
        if (item.is_null()) {
          state_[section].erase(key);
        } else {
          state_[section][key] = item;
        }
        if (std::string(section) == "robots" && !item.is_null() && item.contains("x")) {
          xs_[key].push_back(item["x"].get<double>());
        }
      }
    }
  }

  httplib::Client client_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<int> status_{0};
  mutable std::mutex mutex_;
  std::vector<json> events_;
  json state_;
  std::map<std::string, std::vector<double>> xs_;
};

// A browser that asks for the event stream and then never reads: its socket fills and stalls.
class StalledBrowser {
 public:
  explicit StalledBrowser(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    const int tiny = 1024;
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &tiny, sizeof(tiny));
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0;
    const std::string request = "GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
    connected_ = connected_ && ::write(fd_, request.data(), request.size()) ==
                                   static_cast<ssize_t>(request.size());
  }
  ~StalledBrowser() { ::close(fd_); }
  bool connected() const { return connected_; }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

// A robot the test moves itself: a status every 100 ms, one metre further each time.
class MovingProbe {
 public:
  explicit MovingProbe(int domain) {
    participant_ = std::move(testing::LoopbackParticipant(domain)).value();
    writer_ = std::move(transport::RobotStatusWriter::Create(*participant_)).value();
  }
  ~MovingProbe() {
    writer_.reset();
    participant_.reset();
  }
  // Publishes `steps` statuses at x = 1, 2, ..., one per 100 ms.
  void Move(int steps) {
    for (int i = 1; i <= steps; ++i) {
      RobotStatus status;
      status.robot = RobotId{"probe"};
      status.stamp = fleetmap::Clock::now();
      status.map_from_robot = Pose2{static_cast<double>(i), 0.0, 0.0};
      status.sequence_number = static_cast<uint32_t>(i);
      ASSERT_TRUE(writer_->Write(status).ok());
      std::this_thread::sleep_for(milliseconds(100));
    }
  }

 private:
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::RobotStatusWriter> writer_;
};

// Fused tiles far from anything, each with 600 short walls (about 25 kB of the page's JSON), as
// a server would publish them.
class BigTilePublisher {
 public:
  explicit BigTilePublisher(int domain) {
    participant_ = std::move(testing::LoopbackParticipant(domain)).value();
    writer_ =
        std::move(transport::VectorTileWriter::Create(*participant_, transport::kFusedTilesTopic))
            .value();
  }
  ~BigTilePublisher() {
    writer_.reset();
    participant_.reset();
  }
  void Publish(int index) {
    constexpr double kQuantum = 0.025;
    transport::VectorTileMessage tile;
    tile.robot_id = RobotId{"fleet"};
    tile.tile = TileId{100 + index, 100};
    tile.revision = 1;
    tile.tile_size = 10.0;
    tile.map.frame_id = "fleet";
    tile.map.resolution = 0.05;
    tile.map.epsilon = 0.0707;
    tile.map.lattice = {kQuantum, Point2::Zero()};
    const auto at = [&](int i, int j) {
      return Point2((tile.tile.x * 400 + i) * kQuantum, (tile.tile.y * 400 + j) * kQuantum);
    };
    for (int wall = 0; wall < 600; ++wall) {
      vector_map::Polyline line;
      const int i = 10 + (wall % 30) * 12;
      const int j = 10 + (wall / 30) * 18;
      line.points = {at(i, j), at(i + 8, j + 3)};
      tile.map.obstacles.push_back(std::move(line));
    }
    ASSERT_TRUE(writer_->Write(tile).ok());
  }

 private:
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::VectorTileWriter> writer_;
};

size_t DistinctCount(const std::vector<double>& values) {
  return std::set<double>(values.begin(), values.end()).size();
}

TEST(ViewHttpTest, ServesThePageAndRefusesEverythingElse) {
  const int domain = process::RandomDomainId();
  testing::ViewProcess view(domain);
  ASSERT_GT(view.port(), 0) << view.process().Output();
  httplib::Client client("127.0.0.1", view.port());

  const auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_THAT(page->body, HasSubstr("<title>fleetmap"));
  EXPECT_THAT(page->body, HasSubstr("id=\"robots\""));
  for (const char* file :
       {"/view.js", "/view.css", "/leaflet/leaflet.js", "/leaflet/leaflet.css"}) {
    const auto response = client.Get(file);
    ASSERT_TRUE(response) << file;
    EXPECT_EQ(response->status, 200) << file;
    EXPECT_GT(response->body.size(), 100u) << file;
  }
  // Nothing outside the static folder, however the path is spelled.
  for (const char* path : {"/../CMakeLists.txt", "/%2e%2e/%2e%2e/etc/passwd",
                           "/leaflet/../../view.js", "/..%2f..%2fetc/passwd", "/nope.html"}) {
    const auto response = client.Get(path);
    ASSERT_TRUE(response) << path;
    EXPECT_EQ(response->status, 404) << path;
    EXPECT_THAT(response->body, ::testing::Not(HasSubstr("root:"))) << path;
  }
  // The event stream is gzip for a browser that accepts it (they all do).
  {
    httplib::Client browser("127.0.0.1", view.port());
    browser.set_decompress(false);
    std::string encoding;
    std::string type;
    browser.Get(
        "/events", httplib::Headers{{"Accept-Encoding", "gzip, deflate, br"}},
        [&](const httplib::Response& response) {
          encoding = response.get_header_value("Content-Encoding");
          type = response.get_header_value("Content-Type");
          return false;  // the headers are all this needs
        },
        [](const char*, size_t) { return false; });
    EXPECT_EQ(encoding, "gzip");
    EXPECT_EQ(type, "text/event-stream");
  }
  // No fused map on this empty domain yet.
  EXPECT_EQ(client.Get("/map.png")->status, 404);
  // Read-only: a request that would write is not served.
  const auto post = client.Post("/", "x", "text/plain");
  ASSERT_TRUE(post);
  EXPECT_NE(post->status, 200);
  // An oversize request line is refused, not served.
  const auto oversize = client.Get("/" + std::string(20000, 'a'));
  ASSERT_TRUE(oversize);
  EXPECT_EQ(oversize->status, 414);

  view.process().Signal(SIGTERM);
  EXPECT_EQ(view.process().Wait(seconds(20)), 0) << view.process().Output();
}

TEST(ViewHttpTest, BadOptionsAreClearErrors) {
  const auto missing = testing::RunFleetmap({"view", "--static-dir", "/nonexistent-page"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("/nonexistent-page"));

  const int domain = process::RandomDomainId();
  testing::ViewProcess first(domain);
  ASSERT_GT(first.port(), 0) << first.process().Output();
  const auto taken = testing::RunFleetmap({"view", "--port", std::to_string(first.port()),
                                           "--domain", std::to_string(domain), "--localhost-only"},
                                          seconds(30));
  EXPECT_EQ(taken.exit_code, 2);
  EXPECT_THAT(taken.err, HasSubstr("cannot listen on 127.0.0.1:" + std::to_string(first.port())));
}

TEST(ViewHttpTest, LateBrowsersGetTheWholeStateAndTwentyAtOnceAllFollow) {
  const int domain = process::RandomDomainId();
  testing::LiveFleet fleet(domain, {"alpha"});
  testing::ViewProcess view(domain);
  ASSERT_GT(view.port(), 0) << view.process().Output();

  // The first browser sees the fleet arrive and settle.
  EventStream early(view.port());
  ASSERT_TRUE(early.WaitUntil([](const EventStream& s) {
    return !s.state()["tiles"].empty() && s.state()["robots"].contains("alpha");
  })) << fleet.server().Output();
  size_t tiles = 0;
  auto stable_since = Clock::now();
  while (Clock::now() - stable_since < seconds(3)) {
    std::this_thread::sleep_for(milliseconds(200));
    const size_t now = early.state()["tiles"].size();
    if (now != tiles) stable_since = Clock::now();
    tiles = now;
  }
  ASSERT_GT(tiles, 0u);
  EXPECT_EQ(early.first_event()["type"], "full");

  // Twenty browsers connect late, at once: each is sent the whole state first.
  std::vector<std::unique_ptr<EventStream>> late;
  for (int i = 0; i < 20; ++i) late.push_back(std::make_unique<EventStream>(view.port()));
  for (const auto& stream : late) {
    ASSERT_TRUE(stream->WaitUntil([](const EventStream& s) { return s.event_count() > 0; }));
    const json first = stream->first_event();
    EXPECT_EQ(first["type"], "full");
    EXPECT_EQ(first["tiles"].size(), tiles);
    EXPECT_TRUE(first["robots"].contains("alpha"));
  }
  // ... then deltas: every one of them follows a robot the test moves.
  MovingProbe probe(domain);
  probe.Move(30);
  for (const auto& stream : late) {
    EXPECT_TRUE(stream->WaitUntil([](const EventStream& s) {
      const auto xs = s.xs_of("probe");
      return !xs.empty() && xs.back() == 30.0;
    })) << "a late browser did not follow the probe to x = 30";
    EXPECT_GE(DistinctCount(stream->xs_of("probe")), 5u);
    EXPECT_EQ(stream->state()["tiles"].size(), tiles);
  }
}

TEST(ViewHttpTest, AStalledBrowserIsDroppedWithoutDelayingTheOthers) {
  const int domain = process::RandomDomainId();
  testing::ViewProcess view(domain, {"--max-clients", "2"});
  ASSERT_GT(view.port(), 0) << view.process().Output();

  EventStream reader(view.port());
  ASSERT_TRUE(reader.WaitUntil([](const EventStream& s) { return s.event_count() > 0; }));
  StalledBrowser stalled(view.port());
  ASSERT_TRUE(stalled.connected());
  std::this_thread::sleep_for(milliseconds(500));
  {
    // Two browsers are the most this view serves: the stalled one counts. A stream would outlast
    // the read timeout and fail; a refusal comes back whole.
    httplib::Client third("127.0.0.1", view.port());
    third.set_read_timeout(seconds(5));
    const auto refused = third.Get("/events");
    ASSERT_TRUE(refused) << "the view served a third browser";
    EXPECT_EQ(refused->status, 503);
    EXPECT_THAT(refused->body, HasSubstr("at most 2 browsers"));
  }

  // Far more than the stalled socket can hold: forty dense tiles, and a robot that moves.
  MovingProbe probe(domain);
  BigTilePublisher tiles(domain);
  for (int i = 0; i < 40; ++i) tiles.Publish(i);
  probe.Move(40);
  EXPECT_TRUE(reader.WaitUntil([](const EventStream& s) {
    const auto xs = s.xs_of("probe");
    return s.state()["tiles"].size() == 40 && !xs.empty() && xs.back() == 40.0;
  })) << "the reader has "
      << reader.state()["tiles"].size() << " of 40 tiles";
  EXPECT_GE(DistinctCount(reader.xs_of("probe")), 10u)
      << "the reader's deltas stopped while another browser stalled";

  // The stalled browser is dropped (its socket accepted nothing for the write timeout), which
  // frees its place for a new browser.
  bool admitted = false;
  const auto deadline = Clock::now() + kDeadline;
  while (!admitted && Clock::now() < deadline) {
    EventStream next(view.port());
    admitted = next.WaitUntil([](const EventStream& s) {
      return s.event_count() > 0 || s.status() != 0;  // an event, or the request ended
    }) && next.event_count() > 0;
    if (!admitted) std::this_thread::sleep_for(seconds(1));
  }
  EXPECT_TRUE(admitted) << "the stalled browser was never dropped";
}

TEST(ViewHttpTest, AnEnrolledViewerSeesASecuredFleetAndAnOutsiderNothing) {
  const std::string dir = testing::FreshTempDir("view_secured") + "/fleet";
  ASSERT_EQ(testing::RunFleetmap({"security", "init", "--dir", dir}).exit_code, 0);
  ASSERT_EQ(
      testing::RunFleetmap({"security", "enroll", "--dir", dir, "--robot", "alpha"}).exit_code, 0);
  ASSERT_EQ(
      testing::RunFleetmap({"security", "enroll", "--dir", dir, "--viewer", "watcher"}).exit_code,
      0);
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  process::Subprocess server({testing::kServerBinary, "--security", dir, "--duration", "120",
                              "--no-object-learning", "--no-extrapolation"},
                             env);
  process::Subprocess agent({testing::kAgentBinary, "--security", dir, "--robot-id", "alpha",
                             "--map", testing::kViewTestMap},
                            env);
  testing::ViewProcess enrolled(domain, {"--security", dir, "--identity", "watcher"});
  testing::ViewProcess outsider(domain);
  ASSERT_GT(enrolled.port(), 0) << enrolled.process().Output();
  ASSERT_GT(outsider.port(), 0) << outsider.process().Output();

  EventStream watcher(enrolled.port());
  EXPECT_TRUE(watcher.WaitUntil([](const EventStream& s) {
    return s.state()["robots"].contains("alpha") && !s.state()["tiles"].empty();
  })) << server.Output();
  // By now the outsider has had every chance to see the same; DDS Security gave it nothing.
  EventStream stranger(outsider.port());
  ASSERT_TRUE(stranger.WaitUntil([](const EventStream& s) { return s.event_count() > 0; }));
  std::this_thread::sleep_for(seconds(2));
  EXPECT_TRUE(stranger.state()["robots"].empty());
  EXPECT_TRUE(stranger.state()["tiles"].empty());
}

}  // namespace
}  // namespace fleetmap
