#include "common/grid/pgm.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <streambuf>
#include <system_error>

#include "common/core/file_io.hpp"
#include "common/grid/image_header.hpp"

namespace fleetmap::grid {
namespace {

constexpr int kMaxPgmValue = 65535;
constexpr int kEof = std::char_traits<char>::eof();

bool IsPgmSpace(int c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}
bool IsDigit(int c) { return c >= '0' && c <= '9'; }

// Shows one byte of the input in an error message.
std::string Describe(int c) {
  if (c == kEof) return "end of file";
  if (c >= 0x20 && c < 0x7f) return std::string("'") + static_cast<char>(c) + "'";
  char hex[8];
  std::snprintf(hex, sizeof(hex), "0x%02x", c & 0xff);
  return std::string("byte ") + hex;
}

// A read-only streambuf over memory, so DecodePgm parses without copying.
class MemoryStreambuf : public std::streambuf {
 public:
  explicit MemoryStreambuf(std::string_view bytes) {
    char* begin = const_cast<char*>(bytes.data());  // never written: no put area, no putback
    setg(begin, begin, begin + bytes.size());
  }
};

// Sequential reader over a streambuf that tracks the byte offset for error messages.
class Cursor {
 public:
  explicit Cursor(std::streambuf* buffer) : buffer_(buffer) {}

  int Peek() { return buffer_->sgetc(); }
  int Get() {
    const int c = buffer_->sbumpc();
    if (c != kEof) ++offset_;
    return c;
  }
  // Reads up to `count` bytes; returns how many arrived.
  int64_t Read(char* out, int64_t count) {
    const int64_t got = buffer_->sgetn(out, count);
    offset_ += got;
    return got;
  }
  int64_t offset() const { return offset_; }

  // Skips whitespace and `#` comments (which run to the end of the line).
  void SkipSpaceAndComments() {
    for (;;) {
      const int c = Peek();
      if (IsPgmSpace(c)) {
        Get();
      } else if (c == '#') {
        SkipComment();
      } else {
        return;
      }
    }
  }

  void SkipComment() {
    for (int c = Get(); c != kEof && c != '\n' && c != '\r'; c = Get()) {
    }
  }

 private:
  std::streambuf* buffer_;
  int64_t offset_ = 0;
};

class PgmParser {
 public:
  PgmParser(std::streambuf* buffer, const std::string& name, const PgmReadOptions& options)
      : in_(buffer), name_(name), options_(options) {}

  StatusOr<PgmImage> Parse() {
    PgmEncoding encoding = PgmEncoding::kBinary;
    FLEETMAP_RETURN_IF_ERROR(ParseMagic(&encoding));
    PgmImage image;
    FLEETMAP_ASSIGN_OR_RETURN(const int64_t width, ParseHeaderNumber("width", 1, kMaxDimension));
    FLEETMAP_ASSIGN_OR_RETURN(const int64_t height, ParseHeaderNumber("height", 1, kMaxDimension));
    FLEETMAP_ASSIGN_OR_RETURN(const int64_t max_value,
                              ParseHeaderNumber("maxval", 1, kMaxPgmValue));
    // Both sides are below 2^31, so the product cannot overflow int64.
    const int64_t cells = width * height;
    const ImageHeader header{.format = "PGM",
                             .width = width,
                             .height = height,
                             .channels = 1,
                             .bytes_per_sample = sizeof(uint16_t)};
    FLEETMAP_RETURN_IF_ERROR(
        header.CheckLimits(name_, options_.max_cells, options_.max_decoded_bytes));
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    image.max_value = static_cast<int>(max_value);

    // Exactly one whitespace byte (or a comment ending in a newline) ends the header.
    const int separator = in_.Peek();
    if (separator == '#') {
      in_.SkipComment();
    } else if (IsPgmSpace(separator)) {
      in_.Get();
    } else {
      return Error(separator == kEof ? StatusCode::kDataLoss : StatusCode::kInvalidArgument,
                   "bad header: expected whitespace after maxval, found " + Describe(separator));
    }

    if (encoding == PgmEncoding::kBinary) {
      FLEETMAP_RETURN_IF_ERROR(ParseBinaryPixels(cells, &image));
    } else {
      FLEETMAP_RETURN_IF_ERROR(ParseAsciiPixels(cells, &image));
    }
    FLEETMAP_RETURN_IF_ERROR(CheckTrailingData());
    return image;
  }

 private:
  static constexpr int64_t kMaxDimension = std::numeric_limits<int32_t>::max();

  Status Error(StatusCode code, const std::string& problem) const {
    return Status(code, name_ + ": " + problem);
  }

  Status ParseMagic(PgmEncoding* encoding) {
    const int p = in_.Get();
    const int digit = in_.Get();
    if (p == kEof) return Error(StatusCode::kDataLoss, "empty file, expected a PGM header");
    if (p != 'P' || !IsDigit(digit)) {
      std::string found = Describe(p);
      if (digit != kEof) found.append(" ").append(Describe(digit));
      return Error(StatusCode::kInvalidArgument,
                   "not a PGM file: expected magic 'P5' or 'P2', found " + found);
    }
    if (digit == '5') {
      *encoding = PgmEncoding::kBinary;
    } else if (digit == '2') {
      *encoding = PgmEncoding::kAscii;
    } else {
      return Error(StatusCode::kInvalidArgument,
                   std::string("unsupported Netpbm type P") + static_cast<char>(digit) +
                       ": only grayscale P5 (binary) and P2 (ASCII) are read");
    }
    const int after = in_.Peek();
    if (after == kEof) return Error(StatusCode::kDataLoss, "truncated header after the magic");
    if (!IsPgmSpace(after) && after != '#') {
      return Error(
          StatusCode::kInvalidArgument,
          "not a PGM file: magic must be followed by whitespace, found " + Describe(after));
    }
    return Status::Ok();
  }

  // One unsigned decimal header field, preceded by whitespace or comments, in [min, max].
  StatusOr<int64_t> ParseHeaderNumber(const char* field, int64_t min, int64_t max) {
    in_.SkipSpaceAndComments();
    int c = in_.Peek();
    if (c == kEof) {
      return Error(StatusCode::kDataLoss, std::string("truncated header: missing ") + field);
    }
    if (!IsDigit(c)) {
      return Error(StatusCode::kInvalidArgument,
                   std::string("bad ") + field + ": expected a positive decimal number, found " +
                       Describe(c));
    }
    int64_t value = 0;
    bool too_large = false;
    std::string digits;
    while (IsDigit(c = in_.Peek())) {
      in_.Get();
      if (digits.size() < 24) digits.push_back(static_cast<char>(c));
      if (!too_large) {
        value = value * 10 + (c - '0');
        too_large = value > max;
      }
    }
    if (c != kEof && !IsPgmSpace(c) && c != '#') {
      return Error(StatusCode::kInvalidArgument, std::string("bad ") + field + ": '" + digits +
                                                     "' is followed by " + Describe(c));
    }
    if (too_large) {
      return Error(StatusCode::kInvalidArgument, std::string("bad ") + field + ": " + digits +
                                                     " is above the maximum of " +
                                                     std::to_string(max));
    }
    if (value < min) {
      return Error(StatusCode::kInvalidArgument, std::string("bad ") + field + ": " + digits +
                                                     " is below the minimum of " +
                                                     std::to_string(min));
    }
    return value;
  }

  // Grows with the data actually present, so a lying header on a short file allocates little,
  // and never past `cells` samples, the size the limits were checked against.
  static void Append(uint16_t sample, int64_t cells, std::vector<uint16_t>* pixels) {
    if (pixels->size() == pixels->capacity()) {
      const int64_t doubled =
          std::max<int64_t>(int64_t{1} << 20, 2 * static_cast<int64_t>(pixels->capacity()));
      pixels->reserve(static_cast<size_t>(std::min(cells, doubled)));
    }
    pixels->push_back(sample);
  }

  Status ParseBinaryPixels(int64_t cells, PgmImage* image) {
    const int bytes_per_sample = image->max_value > 255 ? 2 : 1;
    const int64_t expected_bytes = cells * bytes_per_sample;
    std::array<char, 1 << 16> chunk;
    int64_t got_bytes = 0;
    while (got_bytes < expected_bytes) {
      const int64_t want =
          std::min<int64_t>(static_cast<int64_t>(chunk.size()), expected_bytes - got_bytes);
      const int64_t got = in_.Read(chunk.data(), want);
      // Samples never straddle chunks: chunk size and `want` are even whenever samples are 2 bytes,
      // except for a short read at the end of the file, which is truncation anyway.
      for (int64_t i = 0; i + bytes_per_sample <= got; i += bytes_per_sample) {
        const auto hi = static_cast<uint8_t>(chunk[i]);
        const uint16_t sample =
            bytes_per_sample == 1
                ? hi
                : static_cast<uint16_t>((hi << 8) | static_cast<uint8_t>(chunk[i + 1]));
        if (sample > image->max_value) {
          const int64_t index = static_cast<int64_t>(image->pixels.size());
          return PixelAboveMax(index, sample, image);
        }
        Append(sample, cells, &image->pixels);
      }
      got_bytes += got;
      if (got < want) break;
    }
    if (got_bytes < expected_bytes) {
      return Error(StatusCode::kDataLoss, "truncated: expected " + std::to_string(expected_bytes) +
                                              " bytes of pixels (" + std::to_string(image->width) +
                                              " x " + std::to_string(image->height) + " x " +
                                              std::to_string(bytes_per_sample) + "), found " +
                                              std::to_string(got_bytes));
    }
    return Status::Ok();
  }

  Status ParseAsciiPixels(int64_t cells, PgmImage* image) {
    for (int64_t index = 0; index < cells; ++index) {
      in_.SkipSpaceAndComments();
      int c = in_.Peek();
      if (c == kEof) {
        return Error(StatusCode::kDataLoss, "truncated: expected " + std::to_string(cells) +
                                                " pixel values, found " + std::to_string(index));
      }
      if (!IsDigit(c)) {
        return Error(StatusCode::kDataLoss,
                     "bad pixel value at byte " + std::to_string(in_.offset()) +
                         ": expected a decimal number, found " + Describe(c));
      }
      int64_t value = 0;
      while (IsDigit(c = in_.Peek())) {
        in_.Get();
        value = std::min<int64_t>(value * 10 + (c - '0'), kMaxPgmValue + 1);
      }
      if (c != kEof && !IsPgmSpace(c) && c != '#') {
        return Error(StatusCode::kDataLoss, "bad pixel value at byte " +
                                                std::to_string(in_.offset()) +
                                                ": digits followed by " + Describe(c));
      }
      if (value > image->max_value) return PixelAboveMax(index, value, image);
      Append(static_cast<uint16_t>(value), cells, &image->pixels);
    }
    return Status::Ok();
  }

  Status PixelAboveMax(int64_t index, int64_t value, const PgmImage* image) const {
    const std::string shown = value > kMaxPgmValue ? "> 65535" : std::to_string(value);
    return Error(StatusCode::kDataLoss, "pixel (" + std::to_string(index % image->width) + ", " +
                                            std::to_string(index / image->width) + ") is " + shown +
                                            ", above maxval " + std::to_string(image->max_value));
  }

  Status CheckTrailingData() {
    if (options_.allow_trailing_data) return Status::Ok();
    for (int c = in_.Peek(); c != kEof; c = in_.Peek()) {
      if (!IsPgmSpace(c)) {
        return Error(StatusCode::kDataLoss, "unexpected data after the pixels at byte " +
                                                std::to_string(in_.offset()) + " (" + Describe(c) +
                                                ")");
      }
      in_.Get();
    }
    return Status::Ok();
  }

  Cursor in_;
  const std::string& name_;
  const PgmReadOptions& options_;
};

}  // namespace

StatusOr<PgmImage> ParsePgm(std::istream& in, const std::string& name,
                            const PgmReadOptions& options) {
  if (in.rdbuf() == nullptr) return InvalidArgumentError(name + ": no stream to read");
  return PgmParser(in.rdbuf(), name, options).Parse();
}

StatusOr<PgmImage> DecodePgm(std::string_view bytes, const std::string& name,
                             const PgmReadOptions& options) {
  MemoryStreambuf buffer(bytes);
  return PgmParser(&buffer, name, options).Parse();
}

StatusOr<PgmImage> ReadPgm(const std::string& path, const PgmReadOptions& options) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) return NotFoundError(path + ": no such file");
  if (!std::filesystem::is_regular_file(status)) {
    return InvalidArgumentError(path + ": is not a regular file, expected a PGM file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return NotFoundError(path + ": cannot open for reading");
  return ParsePgm(in, path, options);
}

Status ValidatePgmImage(const PgmImage& image, const std::string& name) {
  if (image.width <= 0 || image.height <= 0) {
    return InvalidArgumentError(name + ": image size " + std::to_string(image.width) + " x " +
                                std::to_string(image.height) + " is not positive");
  }
  if (image.max_value < 1 || image.max_value > kMaxPgmValue) {
    return InvalidArgumentError(name + ": maxval " + std::to_string(image.max_value) +
                                " is outside 1..65535");
  }
  const size_t cells = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (image.pixels.size() != cells) {
    return InvalidArgumentError(name + ": " + std::to_string(image.pixels.size()) +
                                " pixels for a " + std::to_string(image.width) + " x " +
                                std::to_string(image.height) + " image");
  }
  const auto max_it = std::max_element(image.pixels.begin(), image.pixels.end());
  if (*max_it > image.max_value) {
    const size_t index = static_cast<size_t>(max_it - image.pixels.begin());
    return InvalidArgumentError(name + ": pixel (" + std::to_string(index % image.width) + ", " +
                                std::to_string(index / image.width) + ") is " +
                                std::to_string(*max_it) + ", above maxval " +
                                std::to_string(image.max_value));
  }
  return Status::Ok();
}

StatusOr<std::string> EncodePgm(const PgmImage& image, PgmEncoding encoding) {
  FLEETMAP_RETURN_IF_ERROR(ValidatePgmImage(image, "PGM image"));
  std::string out = (encoding == PgmEncoding::kBinary ? "P5\n" : "P2\n") +
                    std::to_string(image.width) + " " + std::to_string(image.height) + "\n" +
                    std::to_string(image.max_value) + "\n";
  if (encoding == PgmEncoding::kBinary) {
    const bool wide = image.max_value > 255;
    out.reserve(out.size() + image.pixels.size() * (wide ? 2 : 1));
    for (const uint16_t sample : image.pixels) {
      if (wide) out.push_back(static_cast<char>(sample >> 8));
      out.push_back(static_cast<char>(sample & 0xff));
    }
    return out;
  }
  constexpr size_t kMaxLine = 70;
  size_t line_length = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::string token = std::to_string(image.at(x, y));
      if (line_length > 0 && line_length + 1 + token.size() > kMaxLine) {
        out.push_back('\n');
        line_length = 0;
      }
      if (line_length > 0) {
        out.push_back(' ');
        ++line_length;
      }
      out += token;
      line_length += token.size();
    }
    out.push_back('\n');
    line_length = 0;
  }
  return out;
}

Status WritePgm(const PgmImage& image, const std::string& path, PgmEncoding encoding) {
  FLEETMAP_RETURN_IF_ERROR(ValidatePgmImage(image, path));
  FLEETMAP_ASSIGN_OR_RETURN(const std::string bytes, EncodePgm(image, encoding));
  return WriteFileAtomically(path, bytes);
}

}  // namespace fleetmap::grid
