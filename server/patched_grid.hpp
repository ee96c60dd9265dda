#pragma once

#include <optional>

#include "common/core/robot_status.hpp"
#include "common/core/status.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/map_update_codec.hpp"

namespace fleetmap::server {

// The grid of one robot on a patch wire as the server rebuilds it: each whole map from
// rt/<robot>/map replaces it, each map update (plain or zstd) patches it. An update the grid
// cannot take is refused with the reason and leaves the grid as it was: one that comes before any
// whole map, lies outside the map, carries the wrong number of cells, or (compressed) does not
// inflate to exactly its width x height cells. Inflating allocates at most the map's cells, so a
// lying raw_size costs nothing. An update stamped before the whole map it would patch is stale
// (the map already holds it) and is skipped. Not thread-safe: one owner (the server's control
// thread).
class PatchedGrid {
 public:
  enum class Outcome { kApplied, kStale };

  void Replace(transport::MapMessage map);
  StatusOr<Outcome> Apply(const transport::MapUpdate& update);
  StatusOr<Outcome> Apply(const transport::CompressedMapUpdate& update);

  // The grid with every update applied so far, stamped with the newest update's stamp (the age
  // of its newest evidence); nothing before the first whole map.
  const std::optional<transport::MapMessage>& map() const { return map_; }

 private:
  // Why an update cannot apply now (no map yet), or kStale / kApplied for its stamp.
  StatusOr<Outcome> Judge(Timestamp update_stamp) const;

  std::optional<transport::MapMessage> map_;
  Timestamp whole_map_stamp_;
};

}  // namespace fleetmap::server
