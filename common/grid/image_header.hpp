#pragma once

// The size of a map image as its decoder will hold it, read from the file's first bytes: what
// LoadMapImage checks against its limits before any pixel is allocated.

#include <cstdint>
#include <string>

#include "common/core/status.hpp"

namespace fleetmap::grid {

struct ImageHeader {
  std::string format;  // "PGM", "PNG", "BMP"
  int64_t width = 0;
  int64_t height = 0;
  int channels = 0;          // per pixel, as decoded (OpenCV expands palettes and gray + alpha)
  int bytes_per_sample = 0;  // as decoded: 1, or 2 for 16-bit samples

  // kResourceExhausted, naming `path`, the size and the limit, when the image has more than
  // `max_cells` pixels or decodes to more than `max_decoded_bytes` bytes
  // (width * height * channels * bytes_per_sample). Never overflows.
  Status CheckLimits(const std::string& path, int64_t max_cells, int64_t max_decoded_bytes) const;
};

// Reads the header of a PNG (signature, IHDR, and the chunks before the first IDAT for tRNS) or a
// BMP, without decoding pixels. The channels and sample size are those cv::imread with
// IMREAD_UNCHANGED produces: PNG gray 1; gray + alpha 4; RGB or palette 3, or 4 with a tRNS
// chunk; RGBA 4; 2 bytes per sample at bit depth 16, else 1. BMP is counted as 4 channels of 1
// byte, the most OpenCV makes of one. Errors name the file: kNotFound, kInvalidArgument (not a
// PNG or BMP, or a header that cannot be right), kDataLoss (the file ends inside the header).
StatusOr<ImageHeader> ReadImageHeader(const std::string& path);

}  // namespace fleetmap::grid
