#include "common/sim/terrain.hpp"

namespace fleetmap::sim {

std::string_view TerrainKindName(TerrainKind kind) {
  switch (kind) {
    case TerrainKind::kMaze:
      return "maze";
    case TerrainKind::kOffice:
      return "office";
    case TerrainKind::kUnstructured:
      return "unstructured";
    case TerrainKind::kWarehouse:
      return "warehouse";
  }
  return "?";
}

std::optional<TerrainKind> TerrainKindFromName(std::string_view name) {
  for (TerrainKind kind : {TerrainKind::kMaze, TerrainKind::kOffice, TerrainKind::kUnstructured,
                           TerrainKind::kWarehouse}) {
    if (TerrainKindName(kind) == name) return kind;
  }
  return std::nullopt;
}

std::string_view ObstacleKindName(ObstacleKind kind) {
  switch (kind) {
    case ObstacleKind::kBoundary:
      return "boundary";
    case ObstacleKind::kWall:
      return "wall";
    case ObstacleKind::kFurniture:
      return "furniture";
    case ObstacleKind::kRubble:
      return "rubble";
  }
  return "?";
}

}  // namespace fleetmap::sim
