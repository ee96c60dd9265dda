// A peer that speaks the wire types but sends nonsense: the server drops each bad sample with a
// message naming the robot and the problem, and keeps serving the others.

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <gtest/gtest.h>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include <cstring>
#include <functional>
#include <limits>
#include <sstream>
#include <thread>

#include "common/grid/occupancy_grid.hpp"
#include "common/process/subprocess.hpp"
#include "common/transport/compressed_map_update_writer.hpp"
#include "common/transport/internal/checked_type_support.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/endpoint.hpp"
#include "common/transport/internal/qos.hpp"
#include "common/transport/internal/vector_tile_codec.hpp"
#include "common/transport/map_update_codec.hpp"
#include "common/transport/occupancy_grid_writer.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "common/vector_map/tiled_vector_map.hpp"
#include "fleetmap_msgs/msg/Entity.h"
#include "fleetmap_msgs/msg/RobotStatusPubSubTypes.h"
#include "fleetmap_msgs/msg/VectorTile.h"
#include "nav_msgs/msg/OccupancyGridPubSubTypes.h"
#include "tests/integration/fleet_binaries.hpp"

namespace fleetmap {
namespace {

namespace dds = eprosima::fastdds::dds;
using std::chrono::seconds;

const std::string& kAgent = testing::kAgentBinary;
const std::string& kServer = testing::kServerBinary;
const std::string kMap = std::string(FLEETMAP_TEST_DATA_DIR) + "/maps/trinary_4x3.yaml";
constexpr seconds kDeadline{20};

fleetmap_msgs::msg::dds_::RobotStatus_ StatusOf(const std::string& robot) {
  fleetmap_msgs::msg::dds_::RobotStatus_ status;
  status.robot_id(robot);
  status.map_topic("rt/" + robot + "/map");  // on the grid wire: the server reads rt/<robot>/map
  return status;
}

nav_msgs::msg::dds_::OccupancyGrid_ Grid(uint32_t width, uint32_t height, size_t cells) {
  nav_msgs::msg::dds_::OccupancyGrid_ grid;
  grid.info().width(width);
  grid.info().height(height);
  grid.info().resolution(0.05f);
  grid.info().origin().orientation().w(1.0);
  grid.data(std::vector<int8_t>(cells, 0));
  return grid;
}

// Writes `sample` every 200 ms until the server prints `text`, as a live robot keeps talking
// (status liveliness is renewed by writing; a single early sample could lapse before matching).
// `keep_alive` is called on every round too (to renew the robot's status while its map goes).
template <typename Sample>
bool WriteUntilServerSays(
    dds::DataWriter* writer, Sample& sample, const process::Subprocess& server,
    const std::string& text, const std::function<void()>& keep_alive = [] {}) {
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  while (std::chrono::steady_clock::now() < deadline) {
    keep_alive();
    if (!writer->write(&sample)) return false;
    if (server.WaitForOutput(text, std::chrono::milliseconds(200))) return true;
  }
  return false;
}

// A participant of the test's own, on `domain`, loopback only.
std::unique_ptr<transport::Participant> TestParticipant(int domain) {
  transport::ParticipantOptions options;
  options.domain_id = domain;
  options.localhost_only = true;
  auto participant = transport::Participant::Create(options);
  EXPECT_TRUE(participant.ok()) << participant.status();
  return participant.ok() ? std::move(participant).value() : nullptr;
}

// A type that writes whatever bytes it is given under the name of nav_msgs/OccupancyGrid: a
// hostile or broken peer whose payload lengths lie.
class RawOccupancyGridType : public dds::TopicDataType {
 public:
  RawOccupancyGridType() {
    setName("nav_msgs::msg::dds_::OccupancyGrid_");
    m_typeSize = 1 << 16;
    m_isGetKeyDefined = false;
  }
  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override {
    const auto* bytes = static_cast<std::string*>(data);
    if (bytes->size() > payload->max_size) return false;
    std::memcpy(payload->data, bytes->data(), bytes->size());
    payload->length = static_cast<uint32_t>(bytes->size());
    payload->encapsulation = CDR_LE;
    return true;
  }
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t*, void*) override { return false; }
  std::function<uint32_t()> getSerializedSizeProvider(void* data) override {
    return [data] { return static_cast<uint32_t>(static_cast<std::string*>(data)->size()); };
  }
  void* createData() override { return new std::string(); }
  void deleteData(void* data) override { delete static_cast<std::string*>(data); }
  bool getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) override { return false; }
};

// A RobotStatus writer of the plain generated type, so a test writes any sample it likes.
StatusOr<std::unique_ptr<transport::WriterEndpoint>> RawStatusWriter(
    transport::Participant& participant) {
  return transport::WriterEndpoint::Create(
      participant, transport::kRobotStatusTopic,
      dds::TypeSupport(new fleetmap_msgs::msg::dds_::RobotStatus_PubSubType()),
      transport::RobotStatusQos().writer);
}

TEST(MalformedSamplesTest, ServerDropsBadSamplesAndKeepsServing) {
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  process::Subprocess server({kServer, "--duration", "60"}, env);
  process::Subprocess alpha({kAgent, "--robot-id", "alpha", "--map", kMap, "--wire", "grid"}, env);
  ASSERT_TRUE(server.WaitForOutput("map from alpha", kDeadline)) << server.Output();

  auto participant = TestParticipant(domain);
  ASSERT_NE(participant, nullptr);
  auto status_writer = RawStatusWriter(*participant);
  ASSERT_TRUE(status_writer.ok()) << status_writer.status();
  auto map_writer = transport::WriterEndpoint::Create(
      *participant, transport::RobotMapTopic(RobotId{"gamma"}),
      dds::TypeSupport(new nav_msgs::msg::dds_::OccupancyGrid_PubSubType()),
      transport::OccupancyGridQos().writer);
  ASSERT_TRUE(map_writer.ok()) << map_writer.status();

  // A robot name that is not a ROS name token.
  auto bad_name = StatusOf("bad/robot");
  EXPECT_TRUE(WriteUntilServerSays((*status_writer)->writer(), bad_name, server,
                                   "(malformed): a robot status sample"))
      << server.Output();
  EXPECT_NE(server.Output().find("bad/robot"), std::string::npos);

  // A valid robot whose map says 10 x 10 but carries 5 cells.
  auto gamma = StatusOf("gamma");
  ASSERT_TRUE(WriteUntilServerSays((*status_writer)->writer(), gamma, server, "robot gamma joined"))
      << server.Output();
  const auto gamma_alive = [&] { (*status_writer)->writer()->write(&gamma); };
  auto short_grid = Grid(10, 10, 5);
  EXPECT_TRUE(WriteUntilServerSays((*map_writer)->writer(), short_grid, server,
                                   "dropped a map sample from gamma", gamma_alive))
      << server.Output();
  EXPECT_NE(server.Output().find("10 x 10 cells but carries 5"), std::string::npos);

  // A payload whose data length claims two billion cells in a few bytes: refused before decoding.
  {
    // Its own participant: the type registered under this name must be the raw one.
    auto raw_participant = TestParticipant(domain);
    ASSERT_NE(raw_participant, nullptr);
    auto raw_writer = transport::WriterEndpoint::Create(
        *raw_participant, transport::RobotMapTopic(RobotId{"gamma"}),
        dds::TypeSupport(new RawOccupancyGridType()), transport::OccupancyGridQos().writer);
    ASSERT_TRUE(raw_writer.ok()) << raw_writer.status();
    // A valid 1 x 3 grid, serialized, then its data length patched to 2^31 - 1 cells.
    auto small = Grid(1, 3, 3);
    std::string hostile(nav_msgs::msg::dds_::OccupancyGrid_::getCdrSerializedSize(small) + 4, '\0');
    eprosima::fastcdr::FastBuffer buffer(hostile.data(), hostile.size());
    eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::LITTLE_ENDIANNESS,
                               eprosima::fastcdr::Cdr::DDS_CDR);
    cdr.serialize_encapsulation();
    small.serialize(cdr);
    hostile.resize(cdr.getSerializedDataLength());
    hostile.replace(hostile.size() - 3 - 4, 4, std::string("\xff\xff\xff\x7f", 4));
    EXPECT_TRUE(WriteUntilServerSays((*raw_writer)->writer(), hostile, server,
                                     "malformed OccupancyGrid payload", gamma_alive))
        << server.Output();
    raw_writer->reset();
  }

  // The same peer then sends a good map: it is taken, and alpha was never disturbed.
  auto good_grid = Grid(2, 3, 6);
  EXPECT_TRUE(WriteUntilServerSays((*map_writer)->writer(), good_grid, server,
                                   "map from gamma: 2 x 3 cells", gamma_alive))
      << server.Output();

  map_writer->reset();
  status_writer->reset();
  server.Signal(SIGINT);
  ASSERT_EQ(server.Wait(kDeadline), 0) << server.Output();
  EXPECT_NE(server.Output().find("alpha            active"), std::string::npos) << server.Output();
  EXPECT_NE(server.Output().find("gamma            "), std::string::npos) << server.Output();
}

// Repeats `write` (and renews `keep_alive`) every 200 ms until the server prints `text`.
bool RepeatUntilServerSays(const std::function<bool()>& write, const process::Subprocess& server,
                           const std::string& text, const std::function<void()>& keep_alive) {
  const auto deadline = std::chrono::steady_clock::now() + kDeadline;
  while (std::chrono::steady_clock::now() < deadline) {
    keep_alive();
    if (!write()) return false;
    if (server.WaitForOutput(text, std::chrono::milliseconds(200))) return true;
  }
  return false;
}

// The server's summary row for `robot`: its rejected samples (the sixth column).
uint64_t RejectedInSummary(const std::string& output, const std::string& robot) {
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string name, state;
    uint64_t tiles = 0, maps = 0, bytes = 0, rejected = 0;
    if (fields >> name >> state >> tiles >> maps >> bytes >> rejected && name == robot) {
      return rejected;
    }
  }
  return 0;
}

// A peer on the zstd patch wire (robot gamma, rt/gamma/map_updates_zstd) that sends a patch
// before its map, then corrupt, lying and misplaced patches: each is refused with the robot and
// the reason, counted, and a good patch afterwards is still applied; alpha is never disturbed.
TEST(MalformedSamplesTest, ServerRefusesBadPatchesAndKeepsServing) {
  const int domain = process::RandomDomainId();
  const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                  {"FLEETMAP_LOCALHOST_ONLY", "1"}};
  process::Subprocess server({kServer, "--duration", "60"}, env);
  process::Subprocess alpha(
      {kAgent, "--robot-id", "alpha", "--map", kMap, "--wire", "grid-updates-zstd"}, env);
  ASSERT_TRUE(server.WaitForOutput("map from alpha", kDeadline)) << server.Output();

  auto participant = TestParticipant(domain);
  ASSERT_NE(participant, nullptr);
  auto status_writer = RawStatusWriter(*participant);
  ASSERT_TRUE(status_writer.ok()) << status_writer.status();
  auto map_writer = transport::OccupancyGridWriter::Create(
      *participant, transport::RobotMapTopic(RobotId{"gamma"}));
  ASSERT_TRUE(map_writer.ok()) << map_writer.status();
  auto patch_writer = transport::CompressedMapUpdateWriter::Create(
      *participant, transport::RobotCompressedMapUpdatesTopic(RobotId{"gamma"}));
  ASSERT_TRUE(patch_writer.ok()) << patch_writer.status();

  auto gamma = StatusOf("gamma");
  gamma.map_topic(transport::RobotCompressedMapUpdatesTopic(RobotId{"gamma"}));
  ASSERT_TRUE(WriteUntilServerSays((*status_writer)->writer(), gamma, server,
                                   "robot gamma joined (grid-updates-zstd wire"))
      << server.Output();
  const auto gamma_alive = [&] { (*status_writer)->writer()->write(&gamma); };

  transport::MapUpdate cells;
  cells.x = 2;
  cells.y = 1;
  cells.width = 4;
  cells.height = 3;
  cells.data.assign(12, grid::kOccupiedValue);
  const auto good = transport::CompressMapUpdate(cells, 3);
  ASSERT_TRUE(good.ok()) << good.status();
  const auto send = [&](const transport::CompressedMapUpdate& update) {
    return [&, update] { return (*patch_writer)->Write(update).ok(); };
  };

  // Before any whole map: nothing to patch.
  EXPECT_TRUE(RepeatUntilServerSays(send(*good), server, "before any whole map", gamma_alive))
      << server.Output();

  transport::MapMessage map;
  map.grid = grid::OccupancyGrid(20, 10, 0.05, Pose2{}, grid::kFreeValue);
  EXPECT_TRUE(RepeatUntilServerSays([&] { return (*map_writer)->Write(map).ok(); }, server,
                                    "map from gamma: 20 x 10 cells", gamma_alive))
      << server.Output();

  transport::CompressedMapUpdate corrupt = *good;
  corrupt.data = {0x28, 0xb5, 0x2f, 0xfd, 0x20, 0x0c, 0xff, 0xff, 0xff, 0xff};
  EXPECT_TRUE(RepeatUntilServerSays(send(corrupt), server,
                                    "4 x 3: data: zstd: Data corruption detected", gamma_alive))
      << server.Output();
  transport::CompressedMapUpdate lying = *good;
  lying.raw_size = 4'000'000'000u;
  EXPECT_TRUE(RepeatUntilServerSays(send(lying), server, "raw_size 4000000000 is not", gamma_alive))
      << server.Output();
  transport::CompressedMapUpdate outside = *good;
  outside.x = 18;
  EXPECT_TRUE(RepeatUntilServerSays(send(outside), server, "outside the 20 x 10 map", gamma_alive))
      << server.Output();
  for (const char* refusal : {"refused from gamma (malformed): dropped a map sample from gamma",
                              "before any whole map", "raw_size 4000000000 is not 4 x 3"}) {
    EXPECT_NE(server.Output().find(refusal), std::string::npos) << refusal;
  }

  // A sound patch from the same peer is applied and fused.
  EXPECT_TRUE(RepeatUntilServerSays(send(*good), server,
                                    "map from gamma: 20 x 10 cells at 0.050 m (0 "
                                    "whole, 1 updates",
                                    gamma_alive))
      << server.Output();

  patch_writer->reset();
  map_writer->reset();
  status_writer->reset();
  server.Signal(SIGINT);
  ASSERT_EQ(server.Wait(kDeadline), 0) << server.Output();
  const std::string output = server.Output();
  EXPECT_GE(RejectedInSummary(output, "gamma"), 4u) << output;
  EXPECT_EQ(RejectedInSummary(output, "alpha"), 0u) << output;
  EXPECT_NE(output.find("alpha            active"), std::string::npos) << output;
}

// A server, one well-behaved agent (alpha), and a peer of the test's own that has joined as
// robot gamma on the tile wire and may then send whatever it likes.
class TileWirePeerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const int domain = process::RandomDomainId();
    domain_ = domain;
    const std::map<std::string, std::string> env = {{"FLEETMAP_DOMAIN", std::to_string(domain)},
                                                    {"FLEETMAP_LOCALHOST_ONLY", "1"}};
    server_ = std::make_unique<process::Subprocess>(
        std::vector<std::string>{kServer, "--duration", "60"}, env);
    alpha_ = std::make_unique<process::Subprocess>(
        std::vector<std::string>{kAgent, "--robot-id", "alpha", "--map", kMap}, env);
    ASSERT_TRUE(server_->WaitForOutput("robot alpha joined", kDeadline)) << server_->Output();
    participant_ = TestParticipant(domain);
    ASSERT_NE(participant_, nullptr);
    status_writer_ = Writer(transport::kRobotStatusTopic, transport::RobotStatusTypeSupport(),
                            transport::RobotStatusQos().writer);
    ASSERT_NE(status_writer_, nullptr);
    gamma_ = StatusOf("gamma");
    gamma_.map_topic("rt/fleetmap/robot_tiles");  // on the tile wire
    ASSERT_TRUE(
        WriteUntilServerSays(status_writer_->writer(), gamma_, *server_, "robot gamma joined"))
        << server_->Output();
  }

  std::unique_ptr<transport::WriterEndpoint> Writer(const std::string& topic, dds::TypeSupport type,
                                                    const dds::DataWriterQos& qos) {
    auto writer = transport::WriterEndpoint::Create(*participant_, topic, std::move(type), qos);
    EXPECT_TRUE(writer.ok()) << writer.status();
    return writer.ok() ? std::move(writer).value() : nullptr;
  }

  // Writes `sample` with `writer` (renewing gamma's status too) until the server says `text`.
  template <typename Sample>
  bool SendUntilServerSays(transport::WriterEndpoint& writer, Sample& sample,
                           const std::string& text) {
    return WriteUntilServerSays(writer.writer(), sample, *server_, text,
                                [this] { status_writer_->writer()->write(&gamma_); });
  }

  // Writes `tile` (stamped anew each time, renewing gamma's status too) until the server
  // publishes the fused tile at its key with obstacles on it.
  bool WriteUntilFused(transport::WriterEndpoint& writer,
                       fleetmap_msgs::msg::dds_::VectorTile_& tile) {
    auto wake_up = std::make_shared<WakeUp>();
    auto fused =
        transport::VectorTileReader::Create(*participant_, transport::kFusedTilesTopic, wake_up);
    EXPECT_TRUE(fused.ok()) << fused.status();
    if (!fused.ok()) return false;
    const TileId key{tile.tile_x(), tile.tile_y()};
    const auto deadline = std::chrono::steady_clock::now() + kDeadline;
    while (std::chrono::steady_clock::now() < deadline) {
      tile.stamp(transport::ToIdl(Clock::now()));
      writer.writer()->write(&tile);
      status_writer_->writer()->write(&gamma_);
      wake_up->WaitFor(std::chrono::milliseconds(200));
      for (const transport::TileEvent& event : (*fused)->Drain()) {
        if (event.kind == transport::TileEvent::Kind::kTile && event.tile.tile == key &&
            !event.tile.map.obstacles.empty()) {
          return true;
        }
      }
    }
    return false;
  }

  // Stops the server (after the test's own writers are gone) and returns what it printed.
  std::string StopServer() {
    status_writer_.reset();
    server_->Signal(SIGINT);
    EXPECT_EQ(server_->Wait(kDeadline), 0) << server_->Output();
    return server_->Output();
  }

  int domain_ = 0;
  std::unique_ptr<process::Subprocess> server_;
  std::unique_ptr<process::Subprocess> alpha_;
  std::unique_ptr<transport::Participant> participant_;
  std::unique_ptr<transport::WriterEndpoint> status_writer_;
  fleetmap_msgs::msg::dds_::RobotStatus_ gamma_;
};

// A valid tile of `robot` at (x, y), as an agent's codec writes it: one 2-vertex polyline, one
// point obstacle (layout 5: varint steps of the fleet-frame lattice).
fleetmap_msgs::msg::dds_::VectorTile_ Tile(const std::string& robot, int32_t x = 0, int32_t y = 0) {
  transport::VectorTileMessage message;
  message.robot_id = RobotId{robot};
  message.tile = {x, y};
  message.stamp = Clock::now();
  message.map.epsilon = 0.07;
  message.map.resolution = 0.05;
  const Point2 corner(x * 10.0, y * 10.0);
  message.map.obstacles = {
      vector_map::Polyline{{corner + Point2(0.5, 0.5), corner + Point2(4.5, 0.5)}, false, 0.0},
      vector_map::Polyline{{corner + Point2(2.5, 3.5)}, false, 0.0}};
  auto tile = transport::ToIdl(message);
  EXPECT_TRUE(tile.ok()) << tile.status();
  return tile.ok() ? *tile : fleetmap_msgs::msg::dds_::VectorTile_();
}

// The lattice at the start of every geometry here: quantum 0.025 m (eight bytes, little-endian),
// origin (0, 0).
constexpr uint8_t kLattice[] = {0x9a, 0x99, 0x99, 0x99, 0x99, 0x99, 0x99, 0x3f, 0};

// `body` after that lattice.
std::vector<uint8_t> OnLattice(std::initializer_list<uint8_t> body) {
  std::vector<uint8_t> bytes;
  for (const uint8_t byte : kLattice) bytes.push_back(byte);
  for (const uint8_t byte : body) bytes.push_back(byte);
  return bytes;
}

TEST_F(TileWirePeerTest, ServerRejectsBadTilesCountsThemAndKeepsFusing) {
  auto tile_writer = Writer(transport::kRobotTilesTopic, transport::VectorTileTypeSupport(),
                            transport::VectorTileQos().writer);
  ASSERT_NE(tile_writer, nullptr);
  struct Case {
    const char* expect;
    std::function<void(fleetmap_msgs::msg::dds_::VectorTile_&)> spoil;
  };
  const Case cases[] = {
      {"the polyline count is 100, more than",
       [](auto& t) {
         t.compression(0);
         t.geometry()[std::size(kLattice)] = 100;
       }},
      {"layout_version is 4, this fleetmap reads 5", [](auto& t) { t.layout_version(4); }},
      {"epsilon 0.000000 is not a positive distance", [](auto& t) { t.epsilon(0.0f); }},
      // One polyline whose first vertex is a million steps (25 km) from the fleet origin.
      {"outside its tile",
       [](auto& t) {
         t.compression(0);
         t.geometry(OnLattice({1, 0, 0, 0x80, 0x89, 0x7a, 0, 2, 0, 0, 0, 0}));
       }},
      {"tile_size_mm is 0", [](auto& t) { t.tile_size_mm(0); }},
      {"compression 9 is neither 0 (plain) nor 1 (zstd)", [](auto& t) { t.compression(9); }},
      {"a free polygon has no outer ring",
       [](auto& t) {
         t.compression(0);
         t.geometry(OnLattice({0, 0, 1, 0, 0, 0, 0}));
       }},
  };
  int32_t x = 0;
  for (const Case& c : cases) {
    auto tile = Tile("gamma", x++);  // one instance each, so no bad sample replaces another
    c.spoil(tile);
    EXPECT_TRUE(SendUntilServerSays(*tile_writer, tile, c.expect)) << c.expect << "\n"
                                                                   << server_->Output();
  }
  // A sound tile from the same peer is fused as usual: it comes back on the fused tiles.
  auto good = Tile("gamma", 0, 7);
  EXPECT_TRUE(WriteUntilFused(*tile_writer, good)) << server_->Output();

  tile_writer.reset();
  const std::string output = StopServer();
  // The summary counts gamma's rejected tiles; alpha kept being served.
  std::istringstream lines(output);
  bool saw_gamma = false;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string robot, state, tiles, maps, bytes, rejected;
    fields >> robot >> state >> tiles >> maps >> bytes >> rejected;
    if (robot == "gamma") {
      saw_gamma = true;
      EXPECT_GE(std::stoi(rejected), 6) << line;
      EXPECT_GE(std::stoi(tiles), 1) << line;
    }
    if (robot == "alpha") {
      EXPECT_GE(std::stoi(tiles), 1) << line;
    }
  }
  EXPECT_TRUE(saw_gamma) << output;
}

// What a hostile peer on the same domain tries first, each answered with a refusal that names
// the problem, while the server keeps fusing: keys at the end of the int32 range, stamps from
// the future or before 1970, an empty robot id, another fleet's tile size.
TEST_F(TileWirePeerTest, ServerRefusesFarKeysOddStampsAndForeignSettingsAndKeepsFusing) {
  auto tile_writer = Writer(transport::kRobotTilesTopic, transport::VectorTileTypeSupport(),
                            transport::VectorTileQos().writer);
  ASSERT_NE(tile_writer, nullptr);
  struct Case {
    const char* expect;
    std::function<void(fleetmap_msgs::msg::dds_::VectorTile_&)> spoil;
  };
  const Case cases[] = {
      {"tile (2147483647, 2147483647) lies",
       [](auto& t) {
         t.tile_x(INT32_MAX);
         t.tile_y(INT32_MAX);
         t.compression(0);
         t.geometry(OnLattice({0, 0, 0}));  // no element: decodes anywhere
       }},
      {"ahead of this server's clock",
       [](auto& t) { t.stamp(transport::ToIdl(Clock::now() + std::chrono::hours(24 * 365))); }},
      {"before this server's clock",
       [](auto& t) {
         builtin_interfaces::msg::dds_::Time_ before_1970;
         before_1970.sec(-5);
         t.stamp(before_1970);
       }},
      {"robot_id \"\" of tile", [](auto& t) { t.robot_id(""); }},
      {"this fleet's tiles are 10 m",
       [](auto& t) {
         t.tile_size_mm(20000);  // geometry coded for 10 m tiles would lie outside a 20 m one
         t.compression(0);
         t.geometry(OnLattice({0, 0, 0}));  // no element: decodes anywhere
       }},
  };
  int32_t x = 0;
  for (const Case& c : cases) {
    auto tile = Tile("gamma", 100 + x++);  // one instance each
    c.spoil(tile);
    EXPECT_TRUE(SendUntilServerSays(*tile_writer, tile, c.expect)) << c.expect << "\n"
                                                                   << server_->Output();
  }
  // A far but honest place (1000 km out) is fused like any other.
  auto far = Tile("gamma", 100000);
  EXPECT_TRUE(WriteUntilFused(*tile_writer, far)) << server_->Output();
  // The fused grid cannot span 1000 km: it shows the larger group and says what it left out.
  EXPECT_TRUE(server_->WaitForOutput("leaves 1 out", kDeadline)) << server_->Output();
  tile_writer.reset();
  const std::string output = StopServer();
  EXPECT_NE(output.find("alpha            active"), std::string::npos) << output;
  EXPECT_NE(output.find("stamp out of window"), std::string::npos) << output;
}

// A peer that knows an agent's robot id can neither end that robot nor speak for it.
TEST_F(TileWirePeerTest, APeerCannotDisposeOrOverwriteAnotherAgentsRobot) {
  auto forged = StatusOf("alpha");
  forged.map_topic("rt/fleetmap/robot_tiles");
  EXPECT_TRUE(
      SendUntilServerSays(*status_writer_, forged, "claims robot id alpha, which participant"))
      << server_->Output();
  // Its disposal of alpha's status instance is refused: alpha stays active.
  status_writer_->writer()->dispose(&forged, dds::HANDLE_NIL);
  EXPECT_TRUE(server_->WaitForOutput("disposed robot alpha, which participant", kDeadline))
      << server_->Output();
  // And tiles in alpha's name (an all-free tile over alpha's walls) are refused.
  auto tile_writer = Writer(transport::kRobotTilesTopic, transport::VectorTileTypeSupport(),
                            transport::VectorTileQos().writer);
  ASSERT_NE(tile_writer, nullptr);
  transport::VectorTileMessage all_free;
  all_free.robot_id = RobotId{"alpha"};
  all_free.stamp = Clock::now();
  all_free.map.epsilon = 0.07;
  all_free.map.resolution = 0.05;
  all_free.map.free_space = {
      vector_map::FreePolygon{{{0.0, 0.0}, {9.975, 0.0}, {9.975, 9.975}, {0.0, 9.975}}, {}}};
  auto erasing = transport::ToIdl(all_free).value();
  EXPECT_TRUE(SendUntilServerSays(*tile_writer, erasing, "for robot alpha from participant"))
      << server_->Output();
  tile_writer.reset();
  // An agent started with the id this peer holds (gamma) is told and exits. It waits 5 s for
  // claims, not the default 1 s: on a loaded machine discovery alone can take longer.
  process::Subprocess squatted(
      {kAgent, "--robot-id", "gamma", "--map", kMap, "--claim-wait", "5"},
      {{"FLEETMAP_DOMAIN", std::to_string(domain_)}, {"FLEETMAP_LOCALHOST_ONLY", "1"}});
  status_writer_->writer()->write(&gamma_);
  EXPECT_EQ(squatted.Wait(kDeadline), 2) << squatted.Output();
  EXPECT_NE(squatted.Output().find("robot id gamma is already taken"), std::string::npos)
      << squatted.Output();
  const std::string output = StopServer();
  EXPECT_NE(output.find("alpha            active"), std::string::npos) << output;
  EXPECT_EQ(output.find("robot alpha left"), std::string::npos) << output;
}

// A closed door of `robot`, 0.9 m wide, in its map frame.
fleetmap_msgs::msg::dds_::Entity_ Door(const std::string& robot, const std::string& id) {
  fleetmap_msgs::msg::dds_::Entity_ door;
  door.robot_id(robot);
  door.entity_id(id);
  door.frame_id("map");
  door.entity_class(1);
  door.x({0.1, 0.1});
  door.y({0.0, 0.9});
  door.direction(0.0);
  return door;
}

TEST_F(TileWirePeerTest, ServerRejectsBadEntitiesNamingThemAndKeepsTheGoodOnes) {
  auto entity_writer = Writer(transport::kEntitiesTopic, transport::EntityTypeSupport(),
                              transport::KeyedStateQos().writer);
  ASSERT_NE(entity_writer, nullptr);
  struct Case {
    const char* expect;
    std::function<void(fleetmap_msgs::msg::dds_::Entity_&)> spoil;
  };
  const Case cases[] = {
      {"door_0 of gamma: a door of zero width",
       [](auto& e) {
         e.y({0.0, 0.0});
       }},
      {"door_1 of gamma: unknown entity class 9", [](auto& e) { e.entity_class(9); }},
      {"door_2 of gamma: a coordinate or the direction is not finite",
       [](auto& e) {
         e.x({std::numeric_limits<double>::quiet_NaN(), 0.1});
       }},
      {"door_3 of gamma: a track needs as many stamps and headings as points",
       [](auto& e) {
         e.entity_class(3);
         e.track_stamps({0.0});
       }},
      {"robot id \"bad robot\" is not a ROS 2 name", [](auto& e) { e.robot_id("bad robot"); }},
  };
  int index = 0;
  for (const Case& c : cases) {
    auto entity = Door("gamma", "door_" + std::to_string(index++));
    c.spoil(entity);
    EXPECT_TRUE(SendUntilServerSays(*entity_writer, entity, c.expect)) << c.expect << "\n"
                                                                       << server_->Output();
  }
  // A sound entity from the same peer is taken.
  auto good = Door("gamma", "door_ok");
  entity_writer->writer()->write(&good);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));

  entity_writer.reset();
  const std::string output = StopServer();
  EXPECT_NE(output.find("extrapolation: 1 entities (5 rejected)"), std::string::npos) << output;
  EXPECT_NE(output.find("alpha            active"), std::string::npos) << output;
}

}  // namespace
}  // namespace fleetmap
