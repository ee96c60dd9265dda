#pragma once

// One browser's event stream, gzip-compressed as it goes (zlib). Each piece is flushed with
// Z_SYNC_FLUSH, so the browser can decode an event as soon as it arrives instead of waiting for
// the compressor's next block; the compressor keeps its window across pieces, so the JSON's
// repeated keys and numbers cost little after the first event.

#include <zlib.h>

#include <memory>
#include <string>
#include <string_view>

namespace fleetmap::view {

class GzipStream {
 public:
  // nullptr when zlib cannot set up a compressor (out of memory).
  static std::unique_ptr<GzipStream> Create(int level = Z_DEFAULT_COMPRESSION);
  ~GzipStream();
  GzipStream(const GzipStream&) = delete;
  GzipStream& operator=(const GzipStream&) = delete;

  // The bytes to send for `piece`: everything of it, decodable on arrival.
  std::string Compress(std::string_view piece);

 private:
  GzipStream() = default;
  z_stream stream_{};
};

}  // namespace fleetmap::view
