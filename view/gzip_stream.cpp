#include "view/gzip_stream.hpp"

namespace fleetmap::view {

std::unique_ptr<GzipStream> GzipStream::Create(int level) {
  std::unique_ptr<GzipStream> gzip(new GzipStream());
  // 15 + 16: the largest window, with a gzip header and trailer (Content-Encoding: gzip).
  if (deflateInit2(&gzip->stream_, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    return nullptr;
  }
  return gzip;
}

GzipStream::~GzipStream() { deflateEnd(&stream_); }

std::string GzipStream::Compress(std::string_view piece) {
  std::string out;
  stream_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(piece.data()));
  stream_.avail_in = static_cast<uInt>(piece.size());
  char buffer[16384];
  do {
    stream_.next_out = reinterpret_cast<Bytef*>(buffer);
    stream_.avail_out = sizeof(buffer);
    deflate(&stream_, Z_SYNC_FLUSH);
    out.append(buffer, sizeof(buffer) - stream_.avail_out);
  } while (stream_.avail_out == 0);
  return out;
}

}  // namespace fleetmap::view
