#include "common/transport/internal/vector_tile_codec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/number_format.hpp"
#include "common/transport/internal/conversions.hpp"
#include "common/transport/internal/varint_stream.hpp"
#include "common/transport/internal/zstd_frame.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::transport {
namespace {

using fleetmap_msgs::msg::dds_::VectorTile_;
using vector_map::FreePolygon;
using vector_map::Polyline;

// VectorTile::layout_version of this layout (docs/file-formats.md, "Versions").
constexpr uint8_t kTileLayoutVersion = 5;
// What layouts 3 and 4 hold where this one has layout_version: the low byte of the length of
// their frame_id, "fleet" (6 with its NUL).
constexpr uint8_t kOldLayoutMark = 6;

enum Compression : uint8_t { kPlain = 0, kZstd = 1 };
// zstd level for the geometry: on strings of a few hundred bytes of varints, level 9 saves 0.2 %
// more than level 3 at twice the time (7 against 3 microseconds a tile, docs/results.md).
constexpr int kZstdLevel = 3;
// No tile's geometry comes near this (a 10 m tile of 5 cm cells holds 40 000 cells); a larger
// decompressed size is a hostile or broken sample, refused before anything is allocated.
constexpr size_t kMaxGeometryBytes = TileDecodeLimits{}.max_geometry_bytes;

// The fewest bytes each element takes in the geometry, to bound counts by the bytes left before
// anything is reserved: a vertex is two varints, a polyline its header, half width and two
// vertices, a point its half width and vertex, a ring its size and a vertex, a polygon its ring
// count and a ring.
constexpr size_t kMinVertexBytes = 2;
constexpr size_t kMinPolylineBytes = 2 + 2 * kMinVertexBytes;
constexpr size_t kMinPointBytes = 1 + kMinVertexBytes;
constexpr size_t kMinRingBytes = 1 + kMinVertexBytes;
constexpr size_t kMinPolygonBytes = 1 + kMinRingBytes;

// Steps per tile side: at least one, and at most 2^20 (10 m tiles of 10 micrometre steps, finer
// than any grid), so that step counts stay far from the limits of int64 and of exact doubles.
constexpr double kMinStepsPerSide = 1.0;
constexpr double kMaxStepsPerSide = 1 << 20;

// The tile's lattice in whole steps of the fleet frame: step (i, j) is the point
// (i * quantum + origin_x, j * quantum + origin_y). The same integers times the same quantum from
// either side of a border: seams decode exactly.
class TileLattice {
 public:
  TileLattice(const TileId& tile, double tile_size, double quantum, Point2 origin)
      : quantum_(quantum), origin_(origin) {
    // A vertex may sit a little outside its tile (a cell centre beyond a border that is not on
    // the cell lattice); farther out than a 16th of the side (and a step) means a broken or
    // hostile tile. Bounds in whole steps, so that each vertex costs two integer comparisons.
    const double side = tile_size / quantum;
    const double slack = side / 16 + 1;
    const double corner_x = (tile.x * tile_size - origin.x()) / quantum;
    const double corner_y = (tile.y * tile_size - origin.y()) / quantum;
    min_ = {static_cast<int64_t>(std::ceil(corner_x - slack)),
            static_cast<int64_t>(std::ceil(corner_y - slack))};
    max_ = {static_cast<int64_t>(std::floor(corner_x + side + slack)),
            static_cast<int64_t>(std::floor(corner_y + side + slack))};
  }

  double quantum() const { return quantum_; }
  const Point2& origin() const { return origin_; }

  // Steps of the nearest lattice point, which must lie near the tile.
  StatusOr<std::pair<int64_t, int64_t>> Steps(const Point2& point) const {
    const double i = (point.x() - origin_.x()) / quantum_;
    const double j = (point.y() - origin_.y()) / quantum_;
    // Range first (NaN fails it too), then round half away from zero as std::round does.
    if (!(i >= static_cast<double>(min_.first) - 0.5 &&
          i <= static_cast<double>(max_.first) + 0.5 &&
          j >= static_cast<double>(min_.second) - 0.5 &&
          j <= static_cast<double>(max_.second) + 0.5)) {
      return InvalidArgumentError("a vertex at (" + std::to_string(point.x()) + ", " +
                                  std::to_string(point.y()) + ") lies outside its tile");
    }
    const std::pair<int64_t, int64_t> steps{static_cast<int64_t>(i < 0 ? i - 0.5 : i + 0.5),
                                            static_cast<int64_t>(j < 0 ? j - 0.5 : j + 0.5)};
    if (!Near(steps.first, steps.second)) {
      return InvalidArgumentError("a vertex at (" + std::to_string(point.x()) + ", " +
                                  std::to_string(point.y()) + ") lies outside its tile");
    }
    return steps;
  }

  Point2 Decode(int64_t i, int64_t j) const {
    return {static_cast<double>(i) * quantum_ + origin_.x(),
            static_cast<double>(j) * quantum_ + origin_.y()};
  }

  bool Near(int64_t i, int64_t j) const {
    return i >= min_.first && i <= max_.first && j >= min_.second && j <= max_.second;
  }

 private:
  double quantum_;
  Point2 origin_;
  std::pair<int64_t, int64_t> min_;  // the steps a vertex of this tile may take
  std::pair<int64_t, int64_t> max_;
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

StatusOr<uint32_t> TileSizeMillimetres(double tile_size) {
  const double millimetres = std::round(tile_size * 1000.0);
  if (!std::isfinite(tile_size) || tile_size <= 0.0 || millimetres > UINT32_MAX ||
      millimetres / 1000.0 != tile_size) {
    return InvalidArgumentError("tile_size " + std::to_string(tile_size) +
                                " m is not a positive whole number of millimetres");
  }
  return static_cast<uint32_t>(millimetres);
}

Status CheckQuantum(double quantum, double tile_size) {
  const double steps = tile_size / quantum;
  if (!std::isfinite(quantum) || !(steps >= kMinStepsPerSide && steps <= kMaxStepsPerSide)) {
    return InvalidArgumentError("quantum " + std::to_string(quantum) + " m makes " +
                                std::to_string(steps) + " steps of a " + std::to_string(tile_size) +
                                " m tile side, not 1 to " +
                                std::to_string(static_cast<int>(kMaxStepsPerSide)));
  }
  return Status::Ok();
}

// The lattice the tile is sent on: the map's own, or half-cell steps from the fleet origin.
StatusOr<TileLattice> EncodingLattice(const VectorTileMessage& message) {
  const vector_map::VectorMap& map = message.map;
  const double quantum =
      map.lattice.enabled() ? map.lattice.quantum : vector_map::TileQuantum(map.resolution);
  FLEETMAP_RETURN_IF_ERROR(CheckQuantum(quantum, message.tile_size));
  // The origin as the layout holds it: in [0, quantum).
  const auto in_range = [quantum](double origin) {
    const double offset = origin - std::floor(origin / quantum) * quantum;
    return offset >= quantum ? 0.0 : offset;
  };
  const Point2 origin = map.lattice.enabled() ? Point2(in_range(map.lattice.origin.x()),
                                                       in_range(map.lattice.origin.y()))
                                              : Point2::Zero();
  return TileLattice(message.tile, message.tile_size, quantum, origin);
}

// Writes vertices as steps from the vertex before (the first of the tile from step (0, 0)).
class VertexWriter {
 public:
  VertexWriter(const TileLattice& lattice, VarintWriter* out) : lattice_(lattice), out_(out) {}

  Status Write(const Point2& point) {
    FLEETMAP_ASSIGN_OR_RETURN(const auto steps, lattice_.Steps(point));
    out_->Signed(steps.first - last_.first);
    out_->Signed(steps.second - last_.second);
    last_ = steps;
    return Status::Ok();
  }

 private:
  const TileLattice& lattice_;
  VarintWriter* out_;
  std::pair<int64_t, int64_t> last_{0, 0};
};

// The lattice comes first: the quantum, then a byte that says whether the origin follows (most
// maps' origin is (0, 0): their cell corners lie on the fleet frame's half-cell lattice).
void WriteLattice(const TileLattice& lattice, VarintWriter* out) {
  out->Double(lattice.quantum());
  const bool has_origin = lattice.origin() != Point2::Zero();
  out->Byte(has_origin ? 1 : 0);
  if (has_origin) {
    out->Double(lattice.origin().x());
    out->Double(lattice.origin().y());
  }
}

StatusOr<std::vector<uint8_t>> EncodeGeometry(const vector_map::VectorMap& map,
                                              const TileLattice& lattice) {
  VarintWriter out;
  WriteLattice(lattice, &out);
  VertexWriter vertices(lattice, &out);
  std::vector<const Polyline*> polylines;
  std::vector<const Polyline*> points;
  for (const Polyline& polyline : map.obstacles) {
    if (polyline.points.size() == 1) points.push_back(&polyline);
    if (polyline.points.size() >= 2) polylines.push_back(&polyline);
  }
  out.Unsigned(polylines.size());
  for (const Polyline* polyline : polylines) {
    const size_t n = polyline->points.size();
    const bool closed = polyline->closed && n >= 3;
    out.Unsigned((uint64_t{n} - 2) << 1 | (closed ? 1 : 0));
    FLEETMAP_ASSIGN_OR_RETURN(const uint8_t half_width,
                              HalfWidthSteps(polyline->half_width, map.epsilon));
    out.Byte(half_width);
    for (const Point2& point : polyline->points) FLEETMAP_RETURN_IF_ERROR(vertices.Write(point));
  }
  out.Unsigned(points.size());
  for (const Polyline* point : points) {
    FLEETMAP_ASSIGN_OR_RETURN(const uint8_t half_width,
                              HalfWidthSteps(point->half_width, map.epsilon));
    out.Byte(half_width);
    FLEETMAP_RETURN_IF_ERROR(vertices.Write(point->points[0]));
  }
  out.Unsigned(map.free_space.size());
  const auto write_ring = [&](const std::vector<Point2>& ring) -> Status {
    if (ring.empty()) return InvalidArgumentError("a free ring has no vertex");
    out.Unsigned(ring.size());
    for (const Point2& point : ring) FLEETMAP_RETURN_IF_ERROR(vertices.Write(point));
    return Status::Ok();
  };
  for (const FreePolygon& polygon : map.free_space) {
    out.Unsigned(1 + polygon.holes.size());
    FLEETMAP_RETURN_IF_ERROR(write_ring(polygon.outer));
    for (const auto& hole : polygon.holes) FLEETMAP_RETURN_IF_ERROR(write_ring(hole));
  }
  return std::move(out.bytes());
}

// Reads vertices back, each checked to lie near the tile.
class VertexReader {
 public:
  VertexReader(const TileLattice& lattice, VarintReader* in) : lattice_(lattice), in_(in) {}

  StatusOr<Point2> Read() {
    FLEETMAP_ASSIGN_OR_RETURN(const int64_t dx, in_->Signed("a vertex's x step"));
    FLEETMAP_ASSIGN_OR_RETURN(const int64_t dy, in_->Signed("a vertex's y step"));
    // Wrapping arithmetic: a hostile step may overflow, and then lands far from the tile.
    const auto x = static_cast<int64_t>(static_cast<uint64_t>(last_.first) + dx);
    const auto y = static_cast<int64_t>(static_cast<uint64_t>(last_.second) + dy);
    if (!lattice_.Near(x, y)) {
      return InvalidArgumentError("the vertex ending at geometry byte " +
                                  std::to_string(in_->offset()) + " lies at (" + std::to_string(x) +
                                  ", " + std::to_string(y) + ") lattice steps, outside its tile");
    }
    last_ = {x, y};
    return lattice_.Decode(x, y);
  }

 private:
  const TileLattice& lattice_;
  VarintReader* in_;
  std::pair<int64_t, int64_t> last_{0, 0};
};

// What the tile may still decode to: each count is taken from it before anything is reserved.
class DecodeAllowance {
 public:
  explicit DecodeAllowance(const TileDecodeLimits& limits)
      : vertices_(limits.max_vertices), rings_(limits.max_rings), limits_(limits) {}

  Status TakeVertices(uint64_t n) {
    if (n > vertices_) {
      return ResourceExhaustedError("the tile has more than " +
                                    std::to_string(limits_.max_vertices) +
                                    " vertices, the most a tile may have");
    }
    vertices_ -= static_cast<size_t>(n);
    return Status::Ok();
  }
  Status TakeRings(uint64_t n) {
    if (n > rings_) {
      return ResourceExhaustedError("the tile has more than " + std::to_string(limits_.max_rings) +
                                    " free rings, the most a tile may have");
    }
    rings_ -= static_cast<size_t>(n);
    return Status::Ok();
  }

 private:
  size_t vertices_;
  size_t rings_;
  TileDecodeLimits limits_;
};

// A count read from the bytes, refused if the bytes left cannot hold that many elements.
StatusOr<uint32_t> ReadCount(VarintReader& in, size_t min_bytes_each, const char* what) {
  FLEETMAP_ASSIGN_OR_RETURN(const uint64_t count, in.Unsigned(what));
  if (count > in.remaining() / min_bytes_each) {
    return InvalidArgumentError(std::string(what) + " is " + std::to_string(count) +
                                ", more than the " + std::to_string(in.remaining()) +
                                " bytes left can hold");
  }
  return static_cast<uint32_t>(count);
}

Status DecodeObstacles(VarintReader& in, VertexReader& vertices, double half_width_step,
                       DecodeAllowance& allowance, vector_map::VectorMap* map) {
  FLEETMAP_ASSIGN_OR_RETURN(const uint32_t polylines,
                            ReadCount(in, kMinPolylineBytes, "the polyline count"));
  map->obstacles.reserve(polylines);
  for (uint32_t k = 0; k < polylines; ++k) {
    FLEETMAP_ASSIGN_OR_RETURN(const uint64_t header, in.Unsigned("a polyline's vertex count"));
    const uint64_t n = (header >> 1) + 2;
    Polyline polyline;
    polyline.closed = (header & 1) != 0;
    if (polyline.closed && n < 3) {
      return InvalidArgumentError("polyline " + std::to_string(k) +
                                  " is closed with 2 vertices (a closed one has at least 3)");
    }
    FLEETMAP_ASSIGN_OR_RETURN(const uint8_t half_width, in.Byte("a polyline's half width"));
    polyline.half_width = half_width * half_width_step;
    if (n > in.remaining() / kMinVertexBytes) {
      return InvalidArgumentError("polyline " + std::to_string(k) + " has " + std::to_string(n) +
                                  " vertices, more than the " + std::to_string(in.remaining()) +
                                  " bytes left can hold");
    }
    FLEETMAP_RETURN_IF_ERROR(allowance.TakeVertices(n));
    polyline.points.reserve(static_cast<size_t>(n));
    for (uint64_t i = 0; i < n; ++i) {
      FLEETMAP_ASSIGN_OR_RETURN(Point2 point, vertices.Read());
      polyline.points.push_back(point);
    }
    map->obstacles.push_back(std::move(polyline));
  }
  FLEETMAP_ASSIGN_OR_RETURN(const uint32_t points,
                            ReadCount(in, kMinPointBytes, "the point obstacle count"));
  FLEETMAP_RETURN_IF_ERROR(allowance.TakeVertices(points));
  map->obstacles.reserve(polylines + points);
  for (uint32_t k = 0; k < points; ++k) {
    Polyline point;
    FLEETMAP_ASSIGN_OR_RETURN(const uint8_t half_width, in.Byte("a point's half width"));
    point.half_width = half_width * half_width_step;
    FLEETMAP_ASSIGN_OR_RETURN(Point2 where, vertices.Read());
    point.points.push_back(where);
    map->obstacles.push_back(std::move(point));
  }
  return Status::Ok();
}

Status DecodeFreeSpace(VarintReader& in, VertexReader& vertices, DecodeAllowance& allowance,
                       vector_map::VectorMap* map) {
  FLEETMAP_ASSIGN_OR_RETURN(const uint32_t polygons,
                            ReadCount(in, kMinPolygonBytes, "the free polygon count"));
  map->free_space.reserve(polygons);
  const auto read_ring = [&](std::vector<Point2>* ring) -> Status {
    FLEETMAP_ASSIGN_OR_RETURN(const uint32_t size,
                              ReadCount(in, kMinVertexBytes, "a free ring's vertex count"));
    if (size == 0) return InvalidArgumentError("a free ring has no vertex");
    FLEETMAP_RETURN_IF_ERROR(allowance.TakeVertices(size));
    ring->reserve(size);
    for (uint32_t i = 0; i < size; ++i) {
      FLEETMAP_ASSIGN_OR_RETURN(Point2 point, vertices.Read());
      ring->push_back(point);
    }
    return Status::Ok();
  };
  for (uint32_t k = 0; k < polygons; ++k) {
    FLEETMAP_ASSIGN_OR_RETURN(const uint32_t rings,
                              ReadCount(in, kMinRingBytes, "a free polygon's ring count"));
    if (rings == 0) return InvalidArgumentError("a free polygon has no outer ring");
    FLEETMAP_RETURN_IF_ERROR(allowance.TakeRings(rings));
    FreePolygon polygon;
    FLEETMAP_RETURN_IF_ERROR(read_ring(&polygon.outer));
    polygon.holes.resize(rings - 1);
    for (auto& hole : polygon.holes) FLEETMAP_RETURN_IF_ERROR(read_ring(&hole));
    map->free_space.push_back(std::move(polygon));
  }
  return Status::Ok();
}

Status CheckHeader(const VectorTile_& tile) {
  if (tile.layout_version() != kTileLayoutVersion) {
    const std::string older =
        tile.layout_version() == kOldLayoutMark ? " (layouts 3 and 4 read so)" : "";
    return InvalidArgumentError(
        "layout_version is " + std::to_string(tile.layout_version()) + older +
        ", this fleetmap reads " + std::to_string(kTileLayoutVersion) +
        ": the tile comes from another fleetmap version; agents and server must run the same "
        "version");
  }
  if (tile.compression() != kPlain && tile.compression() != kZstd) {
    return InvalidArgumentError("compression " + std::to_string(tile.compression()) +
                                " is neither 0 (plain) nor 1 (zstd)");
  }
  if (tile.tile_size_mm() == 0) return InvalidArgumentError("tile_size_mm is 0");
  // fastcdr writes a string up to its first NUL, so an id holding one would be another id (and
  // another instance key) once written again: found by fuzz/tile_payload_fuzzer.cpp.
  if (tile.robot_id().find('\0') != std::string::npos) {
    return InvalidArgumentError("robot_id holds a NUL byte");
  }
  if (!std::isfinite(tile.epsilon()) || tile.epsilon() <= 0.0f) {
    return InvalidArgumentError("epsilon " + std::to_string(tile.epsilon()) +
                                " is not a positive distance");
  }
  if (!std::isfinite(tile.resolution()) || tile.resolution() <= 0.0f) {
    return InvalidArgumentError("resolution " + std::to_string(tile.resolution()) +
                                " is not a positive distance");
  }
  return Status::Ok();
}

// The lattice at the start of the geometry, every number checked.
StatusOr<TileLattice> ReadLattice(VarintReader& in, const TileId& tile, double tile_size) {
  FLEETMAP_ASSIGN_OR_RETURN(const double quantum, in.Double("the lattice quantum"));
  FLEETMAP_RETURN_IF_ERROR(CheckQuantum(quantum, tile_size));
  FLEETMAP_ASSIGN_OR_RETURN(const uint8_t has_origin, in.Byte("the lattice origin flag"));
  if (has_origin > 1) {
    return InvalidArgumentError("the lattice origin flag is " + std::to_string(has_origin) +
                                ", neither 0 nor 1");
  }
  Point2 origin = Point2::Zero();
  if (has_origin == 1) {
    FLEETMAP_ASSIGN_OR_RETURN(const double x, in.Double("the lattice origin"));
    FLEETMAP_ASSIGN_OR_RETURN(const double y, in.Double("the lattice origin"));
    for (const double value : {x, y}) {
      if (!(value >= 0.0) || !(value < quantum)) {
        return InvalidArgumentError("lattice origin " + std::to_string(value) +
                                    " m is not within [0, quantum " + std::to_string(quantum) +
                                    " m)");
      }
    }
    origin = Point2(x, y);
  }
  return TileLattice(tile, tile_size, quantum, origin);
}

}  // namespace

StatusOr<VectorTile_> ToIdl(const VectorTileMessage& message) {
  FLEETMAP_ASSIGN_OR_RETURN(const uint32_t tile_size_mm, TileSizeMillimetres(message.tile_size));
  FLEETMAP_ASSIGN_OR_RETURN(const TileLattice lattice, EncodingLattice(message));
  FLEETMAP_ASSIGN_OR_RETURN(std::vector<uint8_t> geometry, EncodeGeometry(message.map, lattice));
  VectorTile_ out;
  out.robot_id(message.robot_id.value);
  out.tile_x(message.tile.x);
  out.tile_y(message.tile.y);
  out.stamp(ToIdl(message.stamp));
  out.layout_version(kTileLayoutVersion);
  out.revision(message.revision);
  out.tile_size_mm(tile_size_mm);
  out.epsilon(static_cast<float>(message.map.epsilon));
  out.resolution(static_cast<float>(message.map.resolution));
  if (geometry.size() > kMaxGeometryBytes) {
    return InvalidArgumentError("the tile's geometry takes " + std::to_string(geometry.size()) +
                                " bytes, more than the " + std::to_string(kMaxGeometryBytes) +
                                " a tile may carry");
  }
  std::vector<uint8_t> compressed = ZstdCompress(geometry, kZstdLevel);
  const bool smaller = !compressed.empty() && compressed.size() < geometry.size();
  out.compression(smaller ? kZstd : kPlain);
  out.geometry(smaller ? std::move(compressed) : std::move(geometry));
  // Refuse here whatever FromIdl would refuse on the other side.
  FLEETMAP_RETURN_IF_ERROR(CheckHeader(out));
  return out;
}

StatusOr<VectorTileMessage> FromIdl(const VectorTile_& tile, const TileDecodeLimits& limits) {
  FLEETMAP_RETURN_IF_ERROR(CheckHeader(tile));
  VectorTileMessage out;
  out.robot_id = RobotId{tile.robot_id()};
  out.tile = TileId{tile.tile_x(), tile.tile_y()};
  out.revision = tile.revision();
  out.stamp = FromIdl(tile.stamp());
  out.tile_size = tile.tile_size_mm() / 1000.0;
  out.map.frame_id = "fleet";
  // float32 on the wire; the decimals the sender's options gave.
  out.map.epsilon = DoubleFromFloat(tile.epsilon());
  out.map.resolution = DoubleFromFloat(tile.resolution());
  const size_t max_bytes = std::min(limits.max_geometry_bytes, kMaxGeometryBytes);
  std::vector<uint8_t> decompressed;
  if (tile.compression() == kZstd) {
    // The frame states its size, checked against the limit before a byte is allocated.
    FLEETMAP_ASSIGN_OR_RETURN(decompressed,
                              ZstdDecompress(tile.geometry(), max_bytes, "the geometry"));
  } else if (tile.geometry().size() > max_bytes) {
    return ResourceExhaustedError("the geometry takes " + std::to_string(tile.geometry().size()) +
                                  " bytes, more than the " + std::to_string(max_bytes) +
                                  " allowed");
  }
  const std::vector<uint8_t>& geometry =
      tile.compression() == kZstd ? decompressed : tile.geometry();
  VarintReader in(
      std::string_view(reinterpret_cast<const char*>(geometry.data()), geometry.size()));
  FLEETMAP_ASSIGN_OR_RETURN(const TileLattice lattice, ReadLattice(in, out.tile, out.tile_size));
  out.map.lattice = {lattice.quantum(), lattice.origin()};
  VertexReader vertices(lattice, &in);
  DecodeAllowance allowance(limits);
  FLEETMAP_RETURN_IF_ERROR(DecodeObstacles(in, vertices, vector_map::HalfWidthStep(out.map.epsilon),
                                           allowance, &out.map));
  FLEETMAP_RETURN_IF_ERROR(DecodeFreeSpace(in, vertices, allowance, &out.map));
  if (in.remaining() != 0) {
    return InvalidArgumentError("the geometry has " + std::to_string(in.remaining()) +
                                " bytes after its last polygon");
  }
  return out;
}

}  // namespace fleetmap::transport
