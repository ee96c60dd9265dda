#include "common/transport/internal/vector_tile_codec.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/transport/internal/conversions.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::transport {
namespace {

using fleetmap_msgs::msg::dds_::VectorTile_;
using vector_map::FreePolygon;
using vector_map::Polyline;

// free_polygon_rings and free_ring_sizes are uint16: the most vertices one wire ring, and the most
// rings one polygon, can have. obstacle_sizes are uint8: longer polylines travel as pieces.
constexpr size_t kMaxWireCount = UINT16_MAX;
constexpr size_t kMaxWirePolyline = UINT8_MAX;
// VectorTile::layout_version of this layout (docs/file-formats.md, "Versions").
constexpr uint8_t kTileLayoutVersion = 4;

// Quantises coordinates relative to one tile's corner. Decoding computes the point as
// (tile index * kTileQuantaPerSide + local) * quantum, an integer times the quantum, so a point on
// a border shared by two tiles decodes to the same double from either tile.
class TileQuantiser {
 public:
  TileQuantiser(const TileId& tile, double tile_size)
      : corner_units_(static_cast<double>(tile.x) * vector_map::kTileQuantaPerSide,
                      static_cast<double>(tile.y) * vector_map::kTileQuantaPerSide),
        quantum_(vector_map::TileQuantum(tile_size)) {}

  double quantum() const { return quantum_; }

  Status Append(const Point2& point, std::vector<int16_t>* xs, std::vector<int16_t>* ys) const {
    FLEETMAP_ASSIGN_OR_RETURN(const int16_t x, Quantise(point.x(), corner_units_.x()));
    FLEETMAP_ASSIGN_OR_RETURN(const int16_t y, Quantise(point.y(), corner_units_.y()));
    xs->push_back(x);
    ys->push_back(y);
    return Status::Ok();
  }

  Point2 Decode(int16_t x, int16_t y) const {
    return {(corner_units_.x() + x) * quantum_, (corner_units_.y() + y) * quantum_};
  }

 private:
  StatusOr<int16_t> Quantise(double coordinate, double corner_units) const {
    const double units = std::round(coordinate / quantum_ - corner_units);
    if (!std::isfinite(units) || units < INT16_MIN || units > INT16_MAX) {
      return InvalidArgumentError("a vertex " +
                                  std::to_string(coordinate - corner_units * quantum_) +
                                  " m from its tile's corner does not fit the tile encoding");
    }
    return static_cast<int16_t>(units);
  }

  Point2 corner_units_;  // the tile's corner in quanta
  double quantum_;
};

// Whole HalfWidthStep(epsilon), rounded up so that a reader never paints an obstacle thinner than
// it was measured; the slack keeps a half width that already is whole steps (as the vectorizer
// makes them on the tile lattice) exact through the division.
StatusOr<uint8_t> HalfWidthSteps(double half_width, double epsilon) {
  if (half_width == 0.0) return 0;
  const double steps = std::ceil(half_width / vector_map::HalfWidthStep(epsilon) - 1e-9);
  if (!(steps >= 0.0 && steps <= vector_map::kMaxHalfWidthSteps)) {
    return InvalidArgumentError("an obstacle half width of " + std::to_string(half_width) +
                                " m is not within epsilon (" + std::to_string(epsilon) + " m)");
  }
  return static_cast<uint8_t>(steps);
}

template <typename T>
uint64_t Sum(const std::vector<T>& values) {
  uint64_t sum = 0;
  for (const T value : values) sum += value;
  return sum;
}

// A vertex may sit a little outside its tile (a cell centre beyond a border that is not on the
// cell lattice); more than this many quanta outside means a broken or hostile tile.
constexpr int kOutsideSlack = vector_map::kTileQuantaPerSide / 16;

Status CheckInsideTile(const std::vector<int16_t>& coordinates, const char* name) {
  for (const int16_t value : coordinates) {
    if (value < -kOutsideSlack || value > vector_map::kTileQuantaPerSide + kOutsideSlack) {
      return InvalidArgumentError(std::string(name) + " value " + std::to_string(value) +
                                  " lies outside its tile (0.." +
                                  std::to_string(vector_map::kTileQuantaPerSide) + " quanta)");
    }
  }
  return Status::Ok();
}

Status CheckSameLength(size_t a, const char* a_name, size_t b, const char* b_name) {
  if (a == b) return Status::Ok();
  return InvalidArgumentError(std::string(a_name) + " has " + std::to_string(a) + " values but " +
                              b_name + " " + std::to_string(b));
}

// A per-element array that may be left empty (meaning 0 for every element).
Status CheckOptionalLength(size_t values, const char* name, size_t elements, const char* what) {
  if (values == 0 || values == elements) return Status::Ok();
  return InvalidArgumentError(std::string(name) + " has " + std::to_string(values) +
                              " values for " + std::to_string(elements) + " " + what);
}

Status CheckObstacleCounts(const VectorTile_& tile) {
  const size_t polylines = tile.obstacle_sizes().size();
  FLEETMAP_RETURN_IF_ERROR(CheckSameLength(tile.obstacle_x().size(), "obstacle_x",
                                           tile.obstacle_y().size(), "obstacle_y"));
  if (Sum(tile.obstacle_sizes()) != tile.obstacle_x().size()) {
    return InvalidArgumentError("obstacle_sizes add up to " +
                                std::to_string(Sum(tile.obstacle_sizes())) + " vertices but " +
                                std::to_string(tile.obstacle_x().size()) + " are given");
  }
  for (size_t k = 0; k < polylines; ++k) {
    if (tile.obstacle_sizes()[k] < 2) {
      return InvalidArgumentError("obstacle_sizes[" + std::to_string(k) + "] is " +
                                  std::to_string(tile.obstacle_sizes()[k]) +
                                  ": a polyline has at least two vertices (point obstacles go in "
                                  "point_x / point_y)");
    }
  }
  FLEETMAP_RETURN_IF_ERROR(CheckOptionalLength(tile.obstacle_half_widths().size(),
                                               "obstacle_half_widths", polylines, "polylines"));
  FLEETMAP_RETURN_IF_ERROR(
      CheckSameLength(tile.point_x().size(), "point_x", tile.point_y().size(), "point_y"));
  FLEETMAP_RETURN_IF_ERROR(CheckOptionalLength(tile.point_half_widths().size(), "point_half_widths",
                                               tile.point_x().size(), "points"));
  FLEETMAP_RETURN_IF_ERROR(CheckInsideTile(tile.obstacle_x(), "obstacle_x"));
  FLEETMAP_RETURN_IF_ERROR(CheckInsideTile(tile.obstacle_y(), "obstacle_y"));
  FLEETMAP_RETURN_IF_ERROR(CheckInsideTile(tile.point_x(), "point_x"));
  return CheckInsideTile(tile.point_y(), "point_y");
}

Status CheckFreeCounts(const VectorTile_& tile) {
  FLEETMAP_RETURN_IF_ERROR(
      CheckSameLength(tile.free_x().size(), "free_x", tile.free_y().size(), "free_y"));
  if (Sum(tile.free_polygon_rings()) != tile.free_ring_sizes().size()) {
    return InvalidArgumentError("free_polygon_rings add up to " +
                                std::to_string(Sum(tile.free_polygon_rings())) + " rings but " +
                                std::to_string(tile.free_ring_sizes().size()) + " are given");
  }
  for (const uint16_t rings : tile.free_polygon_rings()) {
    if (rings == 0) return InvalidArgumentError("a free polygon has no outer ring");
  }
  for (const uint16_t size : tile.free_ring_sizes()) {
    if (size == 0) return InvalidArgumentError("a free ring has no vertex");
  }
  if (Sum(tile.free_ring_sizes()) != tile.free_x().size()) {
    return InvalidArgumentError("free_ring_sizes add up to " +
                                std::to_string(Sum(tile.free_ring_sizes())) + " vertices but " +
                                std::to_string(tile.free_x().size()) + " are given");
  }
  FLEETMAP_RETURN_IF_ERROR(CheckInsideTile(tile.free_x(), "free_x"));
  return CheckInsideTile(tile.free_y(), "free_y");
}

// Everything a tile must satisfy, on the way out and on the way in.
Status CheckTile(const VectorTile_& tile) {
  if (tile.layout_version() != kTileLayoutVersion) {
    return InvalidArgumentError(
        "layout_version is " + std::to_string(tile.layout_version()) + ", this fleetmap reads " +
        std::to_string(kTileLayoutVersion) +
        ": the tile comes from another fleetmap version (3 and older had no such field); agents "
        "and server must run the same version");
  }
  if (!std::isfinite(tile.tile_size()) || tile.tile_size() <= 0.0) {
    return InvalidArgumentError("tile_size " + std::to_string(tile.tile_size()) +
                                " is not a positive number");
  }
  const double expected_quantum = vector_map::TileQuantum(tile.tile_size());
  if (!(std::abs(tile.quantum() - expected_quantum) <= 1e-12 * tile.tile_size())) {
    return InvalidArgumentError("quantum " + std::to_string(tile.quantum()) +
                                " m is not tile_size / " +
                                std::to_string(vector_map::kTileQuantaPerSide));
  }
  if (!std::isfinite(tile.epsilon()) || tile.epsilon() <= 0.0f) {
    return InvalidArgumentError("epsilon " + std::to_string(tile.epsilon()) +
                                " is not a positive distance");
  }
  if (!std::isfinite(tile.resolution()) || tile.resolution() <= 0.0f) {
    return InvalidArgumentError("resolution " + std::to_string(tile.resolution()) +
                                " is not a positive distance");
  }
  FLEETMAP_RETURN_IF_ERROR(CheckObstacleCounts(tile));
  return CheckFreeCounts(tile);
}

// One polyline of two or more vertices. A closed one is written with its first vertex repeated at
// its end (its closing segment; fewer than three vertices have none). More than kMaxWirePolyline
// vertices are written as open pieces of at most kMaxWirePolyline, each starting at the last
// vertex of the one before, so the pieces have exactly the polyline's segments.
Status AppendPolyline(const Polyline& polyline, uint8_t half_width, const TileQuantiser& quantiser,
                      VectorTile_* out) {
  const std::vector<Point2>& points = polyline.points;
  const size_t n = points.size();
  const size_t total = polyline.closed && n >= 3 ? n + 1 : n;
  size_t start = 0;
  while (true) {
    const size_t end = std::min(total, start + kMaxWirePolyline);
    out->obstacle_sizes().push_back(static_cast<uint8_t>(end - start));
    out->obstacle_half_widths().push_back(half_width);
    for (size_t i = start; i < end; ++i) {
      FLEETMAP_RETURN_IF_ERROR(
          quantiser.Append(points[i % n], &out->obstacle_x(), &out->obstacle_y()));
    }
    if (end == total) return Status::Ok();
    start = end - 1;
  }
}

Status AppendFreePolygon(const FreePolygon& polygon, const TileQuantiser& quantiser,
                         VectorTile_* out) {
  if (polygon.holes.size() + 1 > kMaxWireCount) {
    return InvalidArgumentError("a free polygon has " + std::to_string(polygon.holes.size()) +
                                " holes, more than the " + std::to_string(kMaxWireCount - 1) +
                                " a tile can carry");
  }
  out->free_polygon_rings().push_back(static_cast<uint16_t>(1 + polygon.holes.size()));
  const auto append_ring = [&](const std::vector<Point2>& ring) -> Status {
    // A ring cannot be cut into pieces without changing the area it bounds.
    if (ring.size() > kMaxWireCount) {
      return InvalidArgumentError("a free ring has " + std::to_string(ring.size()) +
                                  " vertices, more than the " + std::to_string(kMaxWireCount) +
                                  " a tile can carry");
    }
    out->free_ring_sizes().push_back(static_cast<uint16_t>(ring.size()));
    for (const Point2& point : ring) {
      FLEETMAP_RETURN_IF_ERROR(quantiser.Append(point, &out->free_x(), &out->free_y()));
    }
    return Status::Ok();
  };
  FLEETMAP_RETURN_IF_ERROR(append_ring(polygon.outer));
  for (const auto& hole : polygon.holes) FLEETMAP_RETURN_IF_ERROR(append_ring(hole));
  return Status::Ok();
}

bool AllZero(const std::vector<uint8_t>& values) {
  return std::all_of(values.begin(), values.end(), [](uint8_t value) { return value == 0; });
}

}  // namespace

StatusOr<VectorTile_> ToIdl(const VectorTileMessage& message) {
  if (!std::isfinite(message.tile_size) || message.tile_size <= 0.0) {
    return InvalidArgumentError("tile_size " + std::to_string(message.tile_size) +
                                " is not a positive number");
  }
  const TileQuantiser quantiser(message.tile, message.tile_size);
  VectorTile_ out;
  out.robot_id(message.robot_id.value);
  out.tile_x(message.tile.x);
  out.tile_y(message.tile.y);
  out.stamp(ToIdl(message.stamp));
  out.frame_id(message.map.frame_id);
  out.revision(message.revision);
  out.layout_version(kTileLayoutVersion);
  out.tile_size(message.tile_size);
  out.quantum(quantiser.quantum());
  out.epsilon(static_cast<float>(message.map.epsilon));
  out.resolution(static_cast<float>(message.map.resolution));
  for (const Polyline& polyline : message.map.obstacles) {
    if (polyline.points.empty()) continue;
    FLEETMAP_ASSIGN_OR_RETURN(const uint8_t half_width,
                              HalfWidthSteps(polyline.half_width, message.map.epsilon));
    if (polyline.points.size() == 1) {
      FLEETMAP_RETURN_IF_ERROR(
          quantiser.Append(polyline.points[0], &out.point_x(), &out.point_y()));
      out.point_half_widths().push_back(half_width);
    } else {
      FLEETMAP_RETURN_IF_ERROR(AppendPolyline(polyline, half_width, quantiser, &out));
    }
  }
  // All zero (the paper's method, or no half widths measured) is said with an empty array.
  if (AllZero(out.obstacle_half_widths())) out.obstacle_half_widths().clear();
  if (AllZero(out.point_half_widths())) out.point_half_widths().clear();
  for (const FreePolygon& polygon : message.map.free_space) {
    FLEETMAP_RETURN_IF_ERROR(AppendFreePolygon(polygon, quantiser, &out));
  }
  // Refuse here whatever FromIdl would refuse on the other side.
  FLEETMAP_RETURN_IF_ERROR(CheckTile(out));
  return out;
}

StatusOr<VectorTileMessage> FromIdl(const VectorTile_& tile) {
  FLEETMAP_RETURN_IF_ERROR(CheckTile(tile));

  VectorTileMessage out;
  out.robot_id = RobotId{tile.robot_id()};
  out.tile = TileId{tile.tile_x(), tile.tile_y()};
  out.revision = tile.revision();
  out.stamp = FromIdl(tile.stamp());
  out.tile_size = tile.tile_size();
  out.map.frame_id = tile.frame_id();
  out.map.epsilon = tile.epsilon();
  out.map.resolution = tile.resolution();
  const TileQuantiser quantiser(out.tile, out.tile_size);
  const double half_width_step = vector_map::HalfWidthStep(out.map.epsilon);
  const auto& xs = tile.obstacle_x();
  const auto& ys = tile.obstacle_y();
  out.map.obstacles.reserve(tile.obstacle_sizes().size() + tile.point_x().size());
  size_t vertex = 0;
  for (size_t k = 0; k < tile.obstacle_sizes().size(); ++k) {
    const size_t n = tile.obstacle_sizes()[k];
    const size_t last = vertex + n - 1;
    Polyline polyline;
    // The LinearRing convention: a repeated first vertex closes the polyline.
    polyline.closed = n >= 4 && xs[vertex] == xs[last] && ys[vertex] == ys[last];
    polyline.half_width = tile.obstacle_half_widths().empty()
                              ? 0.0
                              : tile.obstacle_half_widths()[k] * half_width_step;
    const size_t kept = polyline.closed ? n - 1 : n;
    polyline.points.reserve(kept);
    for (size_t i = 0; i < kept; ++i) {
      polyline.points.push_back(quantiser.Decode(xs[vertex + i], ys[vertex + i]));
    }
    vertex += n;
    out.map.obstacles.push_back(std::move(polyline));
  }
  for (size_t i = 0; i < tile.point_x().size(); ++i) {
    Polyline point;
    point.points.push_back(quantiser.Decode(tile.point_x()[i], tile.point_y()[i]));
    point.half_width =
        tile.point_half_widths().empty() ? 0.0 : tile.point_half_widths()[i] * half_width_step;
    out.map.obstacles.push_back(std::move(point));
  }
  size_t ring = 0;
  vertex = 0;
  const auto read_ring = [&]() {
    std::vector<Point2> points;
    points.reserve(tile.free_ring_sizes()[ring]);
    for (uint16_t i = 0; i < tile.free_ring_sizes()[ring]; ++i, ++vertex) {
      points.push_back(quantiser.Decode(tile.free_x()[vertex], tile.free_y()[vertex]));
    }
    ++ring;
    return points;
  };
  for (const uint16_t rings : tile.free_polygon_rings()) {
    FreePolygon polygon;
    polygon.outer = read_ring();
    for (uint16_t h = 1; h < rings; ++h) polygon.holes.push_back(read_ring());
    out.map.free_space.push_back(std::move(polygon));
  }
  return out;
}

}  // namespace fleetmap::transport
