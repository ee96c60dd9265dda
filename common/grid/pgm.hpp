#pragma once

// PGM (portable graymap) images as map_server writes them: P5 (binary) and P2 (ASCII), maxval
// 1..65535. The reader is strict so that a damaged map fails loudly with a message naming the file
// and the problem, and it never trusts a size before checking it against a limit.

#include <cstdint>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::grid {

enum class PgmEncoding : uint8_t {
  kBinary,  // P5: one byte per sample up to maxval 255, else two bytes, most significant first
  kAscii,   // P2: decimal samples separated by whitespace
};

// A grayscale image as stored in a PGM file. Row 0 is the TOP row of the picture, as in the file.
struct PgmImage {
  int width = 0;
  int height = 0;
  int max_value = 255;           // 1..65535; 0 is black, max_value white
  std::vector<uint16_t> pixels;  // row-major, width * height samples in [0, max_value]

  uint16_t at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }

  friend bool operator==(const PgmImage&, const PgmImage&) = default;
};

struct PgmReadOptions {
  // Images with more cells than this fail with kResourceExhausted before any pixel is allocated.
  int64_t max_cells = 400'000'000;
  // Likewise images whose pixels take more bytes than this once read: PgmImage holds every sample
  // in 16 bits, so width * height * 2 bytes. The default, 256 MiB, is 134 million cells.
  int64_t max_decoded_bytes = int64_t{256} << 20;
  // By default only whitespace may follow the pixels; a second image or junk is an error.
  bool allow_trailing_data = false;
};

// Reads a PGM file. Errors: kNotFound (no such file), kInvalidArgument (not a PGM, bad header
// field), kDataLoss (truncated, sample above maxval, trailing data), kResourceExhausted (too big).
// Every message starts with `path`.
StatusOr<PgmImage> ReadPgm(const std::string& path, const PgmReadOptions& options = {});

// Parses a PGM from a stream; `name` prefixes every error message (a file name, usually).
StatusOr<PgmImage> ParsePgm(std::istream& in, const std::string& name,
                            const PgmReadOptions& options = {});

// Parses a PGM held in memory (no copy).
StatusOr<PgmImage> DecodePgm(std::string_view bytes, const std::string& name,
                             const PgmReadOptions& options = {});

// Checks that an image can be written: positive size, maxval in 1..65535, width * height samples,
// none above maxval. `name` prefixes the message.
Status ValidatePgmImage(const PgmImage& image, const std::string& name);

// Serializes a valid image (see ValidatePgmImage); P2 lines stay under 70 characters.
StatusOr<std::string> EncodePgm(const PgmImage& image, PgmEncoding encoding = PgmEncoding::kBinary);

// Writes a valid image to `path`, replacing the file whole (WriteFileAtomically).
Status WritePgm(const PgmImage& image, const std::string& path,
                PgmEncoding encoding = PgmEncoding::kBinary);

}  // namespace fleetmap::grid
