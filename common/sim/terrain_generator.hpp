#pragma once

// Seeded, deterministic terrains for the simulator (docs/simulator.md):
//  - maze: a braided maze (recursive backtracker, then a few walls removed to make loops) on a grid
//    of square cells whose side grows with the terrain (2.5 m at 10 m, 4 m at 80 m);
//  - office: bands of two rows of rooms around a corridor, vertical corridors joining the bands,
//    every room with a door to its corridor, some doors between neighbouring rooms, furniture;
//  - unstructured: irregular rubble blobs, diagonal walls and curved walls, scattered with a
//    clearance between any two obstacles so that the free space stays connected;
//  - warehouse: rows of solid shelf racks of one depth at one period, split by a cross aisle,
//    pillars along the front and back aisles, a few pallets in the aisles: repeated structure,
//    where a map fits one rack period over as well as in its own place.
// Same options (seed included) -> the same Terrain, bit for bit (see random.hpp).
//
// Thread-safety: a TerrainGenerator is immutable; Generate() may run concurrently.

#include <cstdint>

#include "common/core/status.hpp"
#include "common/sim/random.hpp"
#include "common/sim/terrain.hpp"

namespace fleetmap::sim {

// Side bounds (metres). Below the minimum an office or maze has no room; above the maximum the
// 5 cm ground truth (8000 x 8000 cells at 400 m) stops being a reasonable thing to simulate.
inline constexpr double kMinTerrainSize = 5.0;
inline constexpr double kMaxTerrainSize = 400.0;

struct TerrainOptions {
  TerrainKind kind = TerrainKind::kOffice;
  double size = 10.0;  // metres, side of the square, in [kMinTerrainSize, kMaxTerrainSize]
  uint32_t seed = 0;
  double wall_thickness = 0.15;      // metres, interior walls, in (0, 1]
  double boundary_thickness = 0.20;  // metres, the outer wall, in (0, 1]
};

// The boundary wall, `thickness` thick, along the inside of the square [0, size]^2's edge (each
// side runs the full edge, so the corner cells are covered too). For terrains made elsewhere
// too (bench/register's repeated structures).
void AddBoundary(double size, double thickness, Terrain* terrain);

// The warehouse's racks, pillars and pallets (not its boundary) on the square [0, size]^2, drawn
// from `random`; sets terrain->start in the front aisle. Also bench/register's repeated terrain.
void AddWarehouse(double size, Random* random, Terrain* terrain);

class TerrainGenerator {
 public:
  // Errors (kInvalidArgument) name the option: size out of bounds, bad thickness.
  static StatusOr<TerrainGenerator> Create(const TerrainOptions& options);

  const TerrainOptions& options() const { return options_; }
  Terrain Generate() const;

 private:
  explicit TerrainGenerator(const TerrainOptions& options) : options_(options) {}

  TerrainOptions options_;
};

}  // namespace fleetmap::sim
