#pragma once

// Terrains whose structure repeats, for the registration benchmark and the calibration of
// Registration::confidence (issue 31, item 5): places where a crop fits one period over as well
// as in its own place, the failures seen on real pairs (a shelf row shifted by one period).
//  - warehouse: rows of solid shelf racks of one depth at one period, split by a cross aisle,
//    pillars on a lattice, a few pallets left in the aisles (the only thing that tells two aisles
//    apart);
//  - office rows: two bands of identical rooms on either side of a corridor, doors at the same
//    place in every room, a west corridor joining the bands, a desk in some rooms;
//  - corridors: a Manhattan grid of 2 m corridors around identical solid blocks, a few cabinets.
// Each is a 30 m sim::Terrain (boundary wall on the square's edge) drawn from `seed` with
// sim::Random, so a seed gives the same terrain everywhere.
//
// Pure functions: any thread may call them.

#include <cstdint>
#include <string_view>

#include "common/sim/terrain.hpp"

namespace fleetmap::bench {

enum class RepeatedKind : uint8_t { kWarehouse, kOfficeRows, kCorridors };
inline constexpr int kRepeatedKinds = 3;

// "warehouse", "office_rows", "corridors".
std::string_view RepeatedKindName(RepeatedKind kind);

// A `size` metre square terrain (at least 20 m) of the kind. Terrain::kind keeps its default:
// sim::TerrainKind names only the generator's kinds, and the rasterizer does not read it.
sim::Terrain RepeatedTerrain(RepeatedKind kind, double size, uint32_t seed);

}  // namespace fleetmap::bench
