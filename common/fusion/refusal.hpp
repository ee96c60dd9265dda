#pragma once

namespace fleetmap::fusion {

// Why the server refused something a peer sent.
enum class Refusal {
  kMalformed,         // the sample failed its shape or content checks
  kBadRobotId,        // not a ROS 2 name token of at most 64 characters
  kTileOutOfRange,    // a tile key beyond the server's max_coordinate
  kBadTileSettings,   // tile size, epsilon or resolution outside what the server fuses
  kStampOutOfWindow,  // stamped too far ahead of the server's clock, or implausibly old
  kTileQuota,         // the robot already holds its maximum number of tiles
  kByteQuota,         // the robot sends more bytes per second than its quota
  kNotOwner,          // a sample for a robot id that another participant owns
  kTooManyIds,        // the participant already speaks for its maximum number of robot ids
  kNotItself,         // secured: a sample for a robot id other than its writer's identity
  kUnclaimed,         // tiles for a robot id no live status claims, held too long
  kDecodedSize,       // a tile, or a robot's tiles, decode to more vertices, rings or cells
  kMemoryBudget,      // the memory of a robot, its participant, its host or all robots is spent
  kPaintRate,         // the participant asks to paint more cells a second than its quota
  kOutsideRegion,     // a shard's server: the tile lies outside the shard's region
};

const char* RefusalName(Refusal refusal);
// Whether refusing a tile for this reason leaves the server without the robot's whole map (it can
// never hold it), rather than delaying or dropping one revision.
bool CutsTheMap(Refusal refusal);

}  // namespace fleetmap::fusion
