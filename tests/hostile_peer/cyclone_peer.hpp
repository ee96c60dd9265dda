#pragma once

// A DDS participant of another vendor (Eclipse Cyclone DDS, C API) on fleetmap's topics, with the
// types idlc generated from idl/ at build time. It writes robot tiles, fused tiles and robot
// statuses with the QoS of docs/topics.md (reliable, transient local, keep last 1 per instance,
// statuses with a manual-by-topic liveliness lease of 1.5 s), always as XCDR1 (plain CDR), which
// Fast DDS 2.9 reads; and it reads robot tiles, to learn which tiles another robot has.
// Not thread-safe: use from one thread.

#include <dds/dds.h>

#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include "tests/hostile_peer/hostile_samples.hpp"

namespace fleetmap::hostile {

struct PeerOptions {
  int domain_id = 0;
  // UDP on 127.0.0.1 only, no multicast, unicast discovery through the participant ports on
  // 127.0.0.1: what fleetmap's --localhost-only does, so the two find each other. Off: Cyclone's
  // own configuration ($CYCLONEDDS_URI, else its defaults).
  bool localhost_only = true;
};

class CyclonePeer {
 public:
  // Throws std::runtime_error naming the DDS call that failed.
  explicit CyclonePeer(const PeerOptions& options);
  ~CyclonePeer();
  CyclonePeer(const CyclonePeer&) = delete;
  CyclonePeer& operator=(const CyclonePeer&) = delete;

  // Each returns false, with a message in `error`, when Cyclone refuses the sample.
  bool WriteRobotTile(const TileSample& tile, std::string* error);
  bool WriteFusedTile(const TileSample& tile, std::string* error);
  bool WriteStatus(const StatusSample& status, std::string* error);
  // Writes the status and disposes its instance (robot_id) in one sample, as an agent that left.
  bool DisposeStatus(const StatusSample& status, std::string* error);

  // Readers matched by each writer so far (0 for a writer not created yet).
  int MatchedRobotTileReaders() const;
  int MatchedStatusReaders() const;

  // Takes what arrived on robot tiles and returns the keys of `robot`'s live tiles seen so far
  // (the first call starts reading; transient local brings the tiles written before).
  std::set<TileKey> RobotTileKeys(const std::string& robot);

  // The Cyclone configuration of a localhost-only peer with this participant index.
  static std::string LocalhostConfig(int participant_index);

 private:
  // What a writer writes: a robot's state, its status (liveliness), or a server's (exclusive).
  enum class Kind { kRobot, kStatus, kServed };
  dds_entity_t Writer(dds_entity_t* writer, dds_entity_t topic, Kind kind);
  bool WriteTile(dds_entity_t writer, const TileSample& tile, std::string* error);

  dds_entity_t domain_ = 0;
  dds_entity_t participant_ = 0;
  dds_entity_t tiles_topic_ = 0;
  dds_entity_t fused_topic_ = 0;
  dds_entity_t status_topic_ = 0;
  dds_entity_t tiles_writer_ = 0;  // created on first use
  dds_entity_t fused_writer_ = 0;
  dds_entity_t status_writer_ = 0;
  dds_entity_t tiles_reader_ = 0;
  std::set<std::pair<std::string, TileKey>> seen_tiles_;
};

}  // namespace fleetmap::hostile
