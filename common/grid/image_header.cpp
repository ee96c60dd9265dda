#include "common/grid/image_header.hpp"

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace fleetmap::grid {
namespace {

constexpr int64_t kMaxDimension = std::numeric_limits<int32_t>::max();
constexpr char kPngSignature[] = "\x89PNG\r\n\x1a\n";

// Unsigned integers of the file, big-endian (PNG) or little-endian (BMP).
uint32_t Be32(const uint8_t* bytes) {
  return (uint32_t{bytes[0]} << 24) | (uint32_t{bytes[1]} << 16) | (uint32_t{bytes[2]} << 8) |
         bytes[3];
}
uint32_t Le32(const uint8_t* bytes) {
  return bytes[0] | (uint32_t{bytes[1]} << 8) | (uint32_t{bytes[2]} << 16) |
         (uint32_t{bytes[3]} << 24);
}
uint16_t Le16(const uint8_t* bytes) { return static_cast<uint16_t>(bytes[0] | (bytes[1] << 8)); }

bool ReadBytes(std::istream& in, uint8_t* out, std::streamsize count) {
  in.read(reinterpret_cast<char*>(out), count);
  return in.gcount() == count;
}

bool ValidPngDepth(int color_type, int depth) {
  switch (color_type) {
    case 0:  // gray
      return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3:  // palette
      return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2:  // RGB
    case 4:  // gray + alpha
    case 6:  // RGBA
      return depth == 8 || depth == 16;
    default:
      return false;
  }
}

// Whether a tRNS chunk comes before the first IDAT (OpenCV then adds an alpha channel to RGB and
// palette images). The file ending early just ends the search: decoding reports the truncation.
bool HasTransparencyChunk(std::istream& in) {
  std::array<uint8_t, 8> chunk;
  while (ReadBytes(in, chunk.data(), 8)) {
    const uint32_t length = Be32(chunk.data());
    const char* type = reinterpret_cast<const char*>(chunk.data() + 4);
    if (std::memcmp(type, "tRNS", 4) == 0) return true;
    if (std::memcmp(type, "IDAT", 4) == 0 || std::memcmp(type, "IEND", 4) == 0) return false;
    if (length > kMaxDimension) return false;  // not a PNG chunk; the decoder will say so
    in.seekg(static_cast<std::streamoff>(length) + 4, std::ios::cur);  // data and CRC
  }
  return false;
}

StatusOr<ImageHeader> ReadPngHeader(std::istream& in, const std::string& path) {
  // Signature (8), then IHDR: length (4) = 13, "IHDR", width, height, depth, colour type,
  // compression, filter, interlace, CRC (4).
  std::array<uint8_t, 33> bytes;
  if (!ReadBytes(in, bytes.data(), bytes.size())) {
    return DataLossError(path + ": truncated: the file ends inside the PNG header");
  }
  if (Be32(bytes.data() + 8) != 13 || std::memcmp(bytes.data() + 12, "IHDR", 4) != 0) {
    return InvalidArgumentError(path + ": bad PNG header: the first chunk is not a 13-byte IHDR");
  }
  ImageHeader header;
  header.format = "PNG";
  header.width = Be32(bytes.data() + 16);
  header.height = Be32(bytes.data() + 20);
  const int depth = bytes[24];
  const int color_type = bytes[25];
  if (header.width < 1 || header.width > kMaxDimension || header.height < 1 ||
      header.height > kMaxDimension) {
    return InvalidArgumentError(path + ": bad PNG header: size " + std::to_string(header.width) +
                                " x " + std::to_string(header.height) +
                                " (each side must be in 1..2^31-1)");
  }
  if (!ValidPngDepth(color_type, depth)) {
    return InvalidArgumentError(path + ": bad PNG header: colour type " +
                                std::to_string(color_type) + " with bit depth " +
                                std::to_string(depth));
  }
  header.bytes_per_sample = depth == 16 ? 2 : 1;
  switch (color_type) {
    case 0:
      header.channels = 1;  // OpenCV drops a gray image's tRNS
      break;
    case 2:
    case 3:
      header.channels = HasTransparencyChunk(in) ? 4 : 3;
      break;
    default:
      header.channels = 4;  // gray + alpha is expanded to BGRA
      break;
  }
  return header;
}

StatusOr<ImageHeader> ReadBmpHeader(std::istream& in, const std::string& path) {
  // File header (14), then the DIB header: its size (4), then width and height, 16-bit in the
  // 12-byte OS/2 header, 32-bit (height negative for top-down rows) in the others.
  std::array<uint8_t, 26> bytes;
  if (!ReadBytes(in, bytes.data(), bytes.size())) {
    return DataLossError(path + ": truncated: the file ends inside the BMP header");
  }
  ImageHeader header;
  header.format = "BMP";
  if (Le32(bytes.data() + 14) == 12) {
    header.width = Le16(bytes.data() + 18);
    header.height = Le16(bytes.data() + 20);
  } else {
    header.width = static_cast<int32_t>(Le32(bytes.data() + 18));
    header.height = static_cast<int32_t>(Le32(bytes.data() + 22));
    if (header.height < 0) header.height = -header.height;
  }
  if (header.width < 1 || header.height < 1) {
    return InvalidArgumentError(path + ": bad BMP header: size " + std::to_string(header.width) +
                                " x " + std::to_string(header.height));
  }
  header.channels = 4;
  header.bytes_per_sample = 1;
  return header;
}

}  // namespace

Status ImageHeader::CheckLimits(const std::string& path, int64_t max_cells,
                                int64_t max_decoded_bytes) const {
  // Both sides are below 2^31, so the number of cells fits in int64.
  const int64_t cells = width * height;
  const std::string size = std::to_string(width) + " x " + std::to_string(height);
  if (cells > max_cells) {
    return ResourceExhaustedError(path + ": image is " + size + " = " + std::to_string(cells) +
                                  " cells, more than the limit of " + std::to_string(max_cells));
  }
  const int64_t bytes_per_pixel = int64_t{channels} * bytes_per_sample;
  if (bytes_per_pixel > 0 && cells > max_decoded_bytes / bytes_per_pixel) {
    const bool fits = cells <= std::numeric_limits<int64_t>::max() / bytes_per_pixel;
    return ResourceExhaustedError(
        path + ": image is " + size + " with " + std::to_string(channels) + " channel(s) of " +
        std::to_string(8 * bytes_per_sample) + " bits, " +
        (fits ? std::to_string(cells * bytes_per_pixel) : std::string("over 2^63")) +
        " bytes decoded, more than the limit of " + std::to_string(max_decoded_bytes) +
        " bytes (max_decoded_bytes)");
  }
  return Status::Ok();
}

StatusOr<ImageHeader> ReadImageHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (!std::filesystem::exists(path)) return NotFoundError(path + ": no such file");
    return NotFoundError(path + ": cannot open for reading");
  }
  std::array<char, 8> magic{};
  in.read(magic.data(), magic.size());
  const std::streamsize got = in.gcount();
  in.clear();
  in.seekg(0);
  if (got == 8 && std::memcmp(magic.data(), kPngSignature, 8) == 0) {
    return ReadPngHeader(in, path);
  }
  if (got >= 2 && magic[0] == 'B' && magic[1] == 'M') return ReadBmpHeader(in, path);
  if (got == 0) return DataLossError(path + ": empty file, expected an image");
  if (got < 8 && std::memcmp(magic.data(), kPngSignature, static_cast<size_t>(got)) == 0) {
    return DataLossError(path + ": truncated: the file ends inside the PNG signature");
  }
  return InvalidArgumentError(path +
                              ": not a PGM, PNG or BMP image (the only formats read, so that "
                              "their size can be checked before decoding)");
}

}  // namespace fleetmap::grid
