#include "common/metrics/grid_sizes.hpp"

#include <vector>

#include <zlib.h>
#include <zstd.h>

#include "common/vector_map/png.hpp"

namespace fleetmap::metrics {
namespace {

StatusOr<size_t> GzipSize(std::span<const uint8_t> bytes) {
  z_stream stream{};
  // windowBits 15 + 16 writes a gzip header and trailer.
  if (deflateInit2(&stream, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY) != Z_OK) {
    return InternalError("gzip: deflateInit2 failed");
  }
  std::vector<uint8_t> out(deflateBound(&stream, bytes.size()) + 32);
  stream.next_in = const_cast<Bytef*>(bytes.data());
  stream.avail_in = static_cast<uInt>(bytes.size());
  stream.next_out = out.data();
  stream.avail_out = static_cast<uInt>(out.size());
  const int result = deflate(&stream, Z_FINISH);
  const size_t size = stream.total_out;
  deflateEnd(&stream);
  if (result != Z_STREAM_END) return InternalError("gzip: deflate did not finish");
  return size;
}

StatusOr<size_t> ZstdSize(std::span<const uint8_t> bytes) {
  std::vector<uint8_t> out(ZSTD_compressBound(bytes.size()));
  const size_t size = ZSTD_compress(out.data(), out.size(), bytes.data(), bytes.size(), 19);
  if (ZSTD_isError(size)) return InternalError(std::string("zstd: ") + ZSTD_getErrorName(size));
  return size;
}

}  // namespace

StatusOr<CompressedSizes> MeasureBytes(std::span<const uint8_t> bytes) {
  CompressedSizes sizes;
  sizes.raw = bytes.size();
  FLEETMAP_ASSIGN_OR_RETURN(sizes.gzip, GzipSize(bytes));
  FLEETMAP_ASSIGN_OR_RETURN(sizes.zstd, ZstdSize(bytes));
  return sizes;
}

StatusOr<GridSizes> MeasureGridSizes(const grid::OccupancyGrid& grid) {
  GridSizes sizes;
  const auto* cells = reinterpret_cast<const uint8_t*>(grid.data().data());
  FLEETMAP_ASSIGN_OR_RETURN(sizes.cells, MeasureBytes({cells, grid.data().size()}));
  if (!grid.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(const auto png, vector_map::EncodeGridPng(grid));
    sizes.png = png.size();
  }
  return sizes;
}

}  // namespace fleetmap::metrics
