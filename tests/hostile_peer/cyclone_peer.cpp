#include "tests/hostile_peer/cyclone_peer.hpp"

#include <utility>

#include "fleetmap_msgs/msg/RobotStatus.h"
#include "fleetmap_msgs/msg/VectorTile.h"

namespace fleetmap::hostile {
namespace {

using CTile = fleetmap_msgs_msg_dds__VectorTile_;
using CStatus = fleetmap_msgs_msg_dds__RobotStatus_;

// fleetmap's localhost-only participants announce to 128 participant ports on 127.0.0.1; Cyclone
// takes an index below 120 and announces to the ports of indexes up to the maximum.
constexpr int kMaxParticipantIndex = 119;
// fleetmap's participants on domain D - 1 announce to the first three participant ports of domain
// D too (128 ports of 2 reach past the 250 of a domain): a peer there would join the wrong fleet
// (issue 15, "Domains that do not leak"). Starting above them keeps the peer on its own domain.
constexpr int kFirstParticipantIndex = 3;
constexpr dds_duration_t kLivelinessLease = DDS_MSECS(1500);  // docs/topics.md

void Check(dds_return_t result, const std::string& what) {
  if (result < 0) {
    throw std::runtime_error("Cyclone DDS: " + what + " failed: " + dds_strretcode(result));
  }
}

dds_entity_t CheckEntity(dds_entity_t entity, const std::string& what) {
  Check(entity, what);
  return entity;
}

// A view of `values` as a Cyclone sequence; the vector owns the buffer, Cyclone only reads it.
template <typename Sequence, typename T>
Sequence View(const std::vector<T>& values) {
  Sequence sequence{};
  sequence._maximum = static_cast<uint32_t>(values.size());
  sequence._length = static_cast<uint32_t>(values.size());
  sequence._buffer = const_cast<T*>(values.data());
  sequence._release = false;
  return sequence;
}

char* View(const std::string& text) { return const_cast<char*>(text.c_str()); }

builtin_interfaces_msg_dds__Time_ ToC(const WireTime& time) { return {time.sec, time.nanosec}; }

geometry_msgs_msg_dds__Pose2D_ ToC(const double (&pose)[3]) { return {pose[0], pose[1], pose[2]}; }

CTile ToC(const TileSample& tile) {
  CTile out{};
  out.robot_id = View(tile.robot_id);
  out.tile_x = tile.key.x;
  out.tile_y = tile.key.y;
  out.stamp = ToC(tile.stamp);
  out.layout_version = tile.layout_version;
  out.compression = tile.compression;
  out.revision = tile.revision;
  out.tile_size_mm = tile.tile_size_mm;
  out.epsilon = tile.epsilon;
  out.resolution = tile.resolution;
  out.geometry = View<dds_sequence_uint8>(tile.geometry);
  return out;
}

CStatus ToC(const StatusSample& status) {
  CStatus out{};
  out.robot_id = View(status.robot_id);
  out.stamp = ToC(status.stamp);
  out.map_from_robot = ToC(status.map_from_robot);
  out.fleet_from_map = ToC(status.fleet_from_map);
  out.map_topic = View(status.map_topic);
  out.map_width = status.map_width;
  out.map_height = status.map_height;
  out.map_resolution = status.map_resolution;
  out.map_revision = status.map_revision;
  out.maps_published = status.maps_published;
  out.tiles_published = status.tiles_published;
  out.bytes_published = status.bytes_published;
  out.sequence_number = status.sequence_number;
  return out;
}

// docs/topics.md: reliable, transient local, keep last 1 per instance, unlimited instances; plain
// CDR, which is what Fast DDS 2.9 reads (Cyclone could pick XCDR2 otherwise).
dds_qos_t* StateQos() {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_durability(qos, DDS_DURABILITY_TRANSIENT_LOCAL);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 1);
  dds_qset_resource_limits(qos, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  const dds_data_representation_id_t xcdr1[] = {DDS_DATA_REPRESENTATION_XCDR1};
  dds_qset_data_representation(qos, 1, xcdr1);
  // Leaving does not dispose: the tiles stay with the server, as an agent's do.
  dds_qset_writer_data_lifecycle(qos, false);
  return qos;
}

int Matched(dds_entity_t writer) {
  if (writer <= 0) return 0;
  dds_publication_matched_status_t status{};
  if (dds_get_publication_matched_status(writer, &status) < 0) return 0;
  return static_cast<int>(status.current_count);
}

std::string Failed(const char* what, dds_return_t result) {
  return std::string(what) + " failed: " + dds_strretcode(result);
}

}  // namespace

std::string CyclonePeer::LocalhostConfig(int participant_index) {
  return "<CycloneDDS><Domain id=\"any\">"
         "<General><Interfaces><NetworkInterface address=\"127.0.0.1\" multicast=\"false\"/>"
         "</Interfaces><AllowMulticast>false</AllowMulticast></General>"
         "<Discovery><ParticipantIndex>" +
         std::to_string(participant_index) +
         "</ParticipantIndex>"
         "<MaxAutoParticipantIndex>" +
         std::to_string(kMaxParticipantIndex) +
         "</MaxAutoParticipantIndex>"
         "<Peers><Peer address=\"127.0.0.1\"/></Peers>"
         "<SPDPInterval>1s</SPDPInterval></Discovery>"
         "</Domain></CycloneDDS>";
}

CyclonePeer::CyclonePeer(const PeerOptions& options) {
  const auto domain_id = static_cast<dds_domainid_t>(options.domain_id);
  if (options.localhost_only) {
    // The first free participant index from kFirstParticipantIndex: a taken one fails to bind.
    dds_return_t created = DDS_RETCODE_ERROR;
    for (int index = kFirstParticipantIndex; index <= kMaxParticipantIndex && created < 0;
         ++index) {
      created = dds_create_domain(domain_id, LocalhostConfig(index).c_str());
    }
    domain_ = CheckEntity(created, "creating domain " + std::to_string(options.domain_id) +
                                       " with a free participant index");
  }
  participant_ = CheckEntity(dds_create_participant(domain_id, nullptr, nullptr),
                             "creating a participant on domain " + std::to_string(domain_id));
  tiles_topic_ =
      CheckEntity(dds_create_topic(participant_, &fleetmap_msgs_msg_dds__VectorTile__desc,
                                   kRobotTilesTopic, nullptr, nullptr),
                  std::string("creating topic ") + kRobotTilesTopic);
  fused_topic_ =
      CheckEntity(dds_create_topic(participant_, &fleetmap_msgs_msg_dds__VectorTile__desc,
                                   kFusedTilesTopic, nullptr, nullptr),
                  std::string("creating topic ") + kFusedTilesTopic);
  status_topic_ =
      CheckEntity(dds_create_topic(participant_, &fleetmap_msgs_msg_dds__RobotStatus__desc,
                                   kRobotStatusTopic, nullptr, nullptr),
                  std::string("creating topic ") + kRobotStatusTopic);
}

CyclonePeer::~CyclonePeer() {
  // Deleting the domain (or the participant) deletes every entity in it.
  dds_delete(domain_ > 0 ? domain_ : participant_);
}

dds_entity_t CyclonePeer::Writer(dds_entity_t* writer, dds_entity_t topic, Kind kind) {
  if (*writer > 0) return *writer;
  dds_qos_t* qos = StateQos();
  if (kind == Kind::kStatus) {
    dds_qset_liveliness(qos, DDS_LIVELINESS_MANUAL_BY_TOPIC, kLivelinessLease);
  }
  // docs/standby.md: what a server serves has exclusive ownership (strength 0 here, the least).
  if (kind == Kind::kServed) dds_qset_ownership(qos, DDS_OWNERSHIP_EXCLUSIVE);
  *writer = dds_create_writer(participant_, topic, qos, nullptr);
  dds_delete_qos(qos);
  return *writer;
}

bool CyclonePeer::WriteTile(dds_entity_t writer, const TileSample& tile, std::string* error) {
  if (writer < 0) {
    *error = Failed("creating a tile writer", writer);
    return false;
  }
  const CTile sample = ToC(tile);
  const dds_return_t written = dds_write(writer, &sample);
  if (written < 0) *error = Failed("writing a tile", written);
  return written >= 0;
}

bool CyclonePeer::WriteRobotTile(const TileSample& tile, std::string* error) {
  return WriteTile(Writer(&tiles_writer_, tiles_topic_, Kind::kRobot), tile, error);
}

bool CyclonePeer::WriteFusedTile(const TileSample& tile, std::string* error) {
  return WriteTile(Writer(&fused_writer_, fused_topic_, Kind::kServed), tile, error);
}

bool CyclonePeer::WriteStatus(const StatusSample& status, std::string* error) {
  const dds_entity_t writer = Writer(&status_writer_, status_topic_, Kind::kStatus);
  if (writer < 0) {
    *error = Failed("creating the status writer", writer);
    return false;
  }
  const CStatus sample = ToC(status);
  const dds_return_t written = dds_write(writer, &sample);
  if (written < 0) *error = Failed("writing a status", written);
  return written >= 0;
}

bool CyclonePeer::DisposeStatus(const StatusSample& status, std::string* error) {
  const dds_entity_t writer = Writer(&status_writer_, status_topic_, Kind::kStatus);
  if (writer < 0) {
    *error = Failed("creating the status writer", writer);
    return false;
  }
  // writedispose carries the whole sample: a key-only dispose is not understood by Fast DDS 2.9.
  const CStatus sample = ToC(status);
  const dds_return_t written = dds_writedispose(writer, &sample);
  if (written < 0) *error = Failed("disposing a status", written);
  return written >= 0;
}

int CyclonePeer::MatchedRobotTileReaders() const { return Matched(tiles_writer_); }

int CyclonePeer::MatchedStatusReaders() const { return Matched(status_writer_); }

std::set<TileKey> CyclonePeer::RobotTileKeys(const std::string& robot) {
  if (tiles_reader_ <= 0) {
    dds_qos_t* qos = StateQos();
    // Other participants' tiles only: its own forged ones are not what the victim has.
    dds_qset_ignorelocal(qos, DDS_IGNORELOCAL_PARTICIPANT);
    tiles_reader_ = dds_create_reader(participant_, tiles_topic_, qos, nullptr);
    dds_delete_qos(qos);
    if (tiles_reader_ < 0) return {};
  }
  constexpr int kBatch = 64;
  void* samples[kBatch] = {};
  dds_sample_info_t infos[kBatch];
  while (true) {
    const dds_return_t taken = dds_take(tiles_reader_, samples, infos, kBatch, kBatch);
    if (taken <= 0) break;
    for (int i = 0; i < taken; ++i) {
      const auto* tile = static_cast<const CTile*>(samples[i]);
      if (!infos[i].valid_data || tile->robot_id == nullptr) continue;
      seen_tiles_.insert({tile->robot_id, TileKey{tile->tile_x, tile->tile_y}});
    }
    dds_return_loan(tiles_reader_, samples, taken);
  }
  std::set<TileKey> keys;
  for (const auto& [owner, key] : seen_tiles_) {
    if (owner == robot) keys.insert(key);
  }
  return keys;
}

}  // namespace fleetmap::hostile
