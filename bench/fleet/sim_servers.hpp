#pragma once

// The fleetmap-server processes of a simulated fleet run: one server, or (`fleetmap sim --shards
// K`, docs/shards.md) K shard servers, each fusing a strip of the terrain, the aggregator that
// joins their grids into rt/fleetmap/map, and a reference server that fuses every region in the
// same run on its own map topic, so that the report can compare the sharded map with one server's
// on the same inputs.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/core/shard_regions.hpp"
#include "common/core/status.hpp"
#include "common/process/subprocess.hpp"

namespace fleetmap::bench {

// The reference server's shard name: its grid is on rt/fleetmap/<kReferenceShard>/map.
inline constexpr char kReferenceShard[] = "reference";

// K strips of the terrain along x, each size / K wide; the outer strips reach far beyond the
// terrain, so that no robot's tile lies on no region.
std::vector<ShardRegion> TerrainStrips(double size, int shards);

class SimServers {
 public:
  // `server_args`: what every server gets (the binary first); `shards` < 2: one server.
  static StatusOr<std::unique_ptr<SimServers>> Start(const std::vector<std::string>& server_args,
                                                     const std::map<std::string, std::string>& env,
                                                     double terrain_size, int shards);
  ~SimServers();

  // The fusing servers (the shards, or the one server): what the run's figures count.
  const std::vector<std::unique_ptr<process::Subprocess>>& fusing() const { return fusing_; }
  const std::vector<ShardRegion>& regions() const { return regions_; }
  // Summed over the fusing servers, now.
  double CpuSeconds() const;
  int64_t RssBytes() const;
  int64_t PeakRssBytes() const;
  // Everything the servers printed, each under its name.
  std::string Output() const;
  // SIGINT to all, then waits.
  void Stop();

 private:
  SimServers() = default;

  std::vector<ShardRegion> regions_;
  std::string shards_file_;
  std::vector<std::unique_ptr<process::Subprocess>> fusing_;
  std::vector<std::string> names_;  // of fusing_
  std::unique_ptr<process::Subprocess> aggregator_;
  std::unique_ptr<process::Subprocess> reference_;
};

}  // namespace fleetmap::bench
