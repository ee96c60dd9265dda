#include "view/gzip_stream.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <string>

namespace fleetmap::view {
namespace {

// A browser's side: one inflater for the whole stream, fed piece by piece.
class Gunzip {
 public:
  Gunzip() { inflateInit2(&stream_, 15 + 16); }
  ~Gunzip() { inflateEnd(&stream_); }
  std::string Feed(const std::string& piece) {
    std::string out;
    stream_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(piece.data()));
    stream_.avail_in = static_cast<uInt>(piece.size());
    char buffer[4096];
    do {
      stream_.next_out = reinterpret_cast<Bytef*>(buffer);
      stream_.avail_out = sizeof(buffer);
      const int result = inflate(&stream_, Z_SYNC_FLUSH);
      EXPECT_TRUE(result == Z_OK || result == Z_BUF_ERROR) << result;
      out.append(buffer, sizeof(buffer) - stream_.avail_out);
    } while (stream_.avail_out == 0);
    return out;
  }

 private:
  z_stream stream_{};
};

TEST(GzipStreamTest, EachPieceDecodesWholeOnArrival) {
  auto gzip = GzipStream::Create();
  ASSERT_NE(gzip, nullptr);
  Gunzip browser;
  const std::string first = "data: {\"type\":\"full\",\"tiles\":{}}\n\n";
  const std::string second = "data: {\"type\":\"delta\",\"seq\":1}\n\n";
  EXPECT_EQ(browser.Feed(gzip->Compress(first)), first);
  EXPECT_EQ(browser.Feed(gzip->Compress(second)), second);
}

TEST(GzipStreamTest, RepeatedJsonShrinks) {
  auto gzip = GzipStream::Create();
  ASSERT_NE(gzip, nullptr);
  std::string event = "data: {\"robots\":{";
  for (int i = 0; i < 200; ++i) event += "\"robot\":{\"x\":1.25,\"y\":3.5,\"state\":\"live\"},";
  event += "}}\n\n";
  const std::string compressed = gzip->Compress(event);
  EXPECT_LT(compressed.size() * 10, event.size());
  Gunzip browser;
  EXPECT_EQ(browser.Feed(compressed), event);
}

}  // namespace
}  // namespace fleetmap::view
