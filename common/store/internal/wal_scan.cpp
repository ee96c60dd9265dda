#include "common/store/internal/wal_scan.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

namespace fleetmap::store::internal {
namespace {

constexpr int64_t kHeaderBytes = 32;
constexpr int64_t kFrameHeaderBytes = 24;
constexpr uint32_t kMagicLittleEndian = 0x377f0682;  // checksums over little-endian words
constexpr uint32_t kMagicBigEndian = 0x377f0683;     // checksums over big-endian words
constexpr uint32_t kFormatVersion = 3007000;
// The wal-index header at the start of -shm (two copies of 48 bytes), in the host's byte order.
constexpr size_t kIndexHeaderBytes = 48;
constexpr size_t kIndexMaxFrameOffset = 16;
constexpr size_t kIndexSaltOffset = 32;

uint32_t BigEndian32(const uint8_t* bytes) {
  return (uint32_t{bytes[0]} << 24) | (uint32_t{bytes[1]} << 16) | (uint32_t{bytes[2]} << 8) |
         uint32_t{bytes[3]};
}

uint32_t LittleEndian32(const uint8_t* bytes) {
  return (uint32_t{bytes[3]} << 24) | (uint32_t{bytes[2]} << 16) | (uint32_t{bytes[1]} << 8) |
         uint32_t{bytes[0]};
}

// SQLite's WAL checksum: over pairs of 32-bit words, continuing from (s0, s1). `size` is a
// multiple of 8.
void Checksum(bool big_endian, const uint8_t* data, size_t size, uint32_t* s0, uint32_t* s1) {
  for (size_t i = 0; i + 8 <= size; i += 8) {
    const uint32_t a = big_endian ? BigEndian32(data + i) : LittleEndian32(data + i);
    const uint32_t b = big_endian ? BigEndian32(data + i + 4) : LittleEndian32(data + i + 4);
    *s0 += a + *s1;
    *s1 += b + *s0;
  }
}

// The frames the last writer's wal-index counts as committed, if the -shm is of the WAL whose
// header salts are `salts` (8 bytes); -1 otherwise.
int64_t WriterCommittedFrames(const std::string& shm_path, const uint8_t* salts) {
  std::ifstream shm(shm_path, std::ios::binary);
  std::array<uint8_t, 2 * kIndexHeaderBytes> header{};
  if (!shm.read(reinterpret_cast<char*>(header.data()), header.size())) return -1;
  // Both copies agree (a writer was not killed mid-update) and the index was initialised.
  if (std::memcmp(header.data(), header.data() + kIndexHeaderBytes, kIndexHeaderBytes) != 0) {
    return -1;
  }
  uint32_t version = 0;
  std::memcpy(&version, header.data(), sizeof(version));
  if (version != kFormatVersion || header[12] != 1) return -1;
  if (std::memcmp(header.data() + kIndexSaltOffset, salts, 8) != 0) return -1;
  uint32_t max_frame = 0;
  std::memcpy(&max_frame, header.data() + kIndexMaxFrameOffset, sizeof(max_frame));
  return max_frame;
}

}  // namespace

WalScan ScanWal(const std::string& database_path) {
  WalScan scan;
  const std::string wal_path = database_path + "-wal";
  std::error_code error;
  if (!std::filesystem::is_regular_file(wal_path, error)) return scan;
  scan.found = true;
  scan.bytes = static_cast<int64_t>(std::filesystem::file_size(wal_path, error));
  std::ifstream wal(wal_path, std::ios::binary);
  std::array<uint8_t, kHeaderBytes> header{};
  if (!wal.read(reinterpret_cast<char*>(header.data()), header.size())) return scan;
  const uint32_t magic = BigEndian32(&header[0]);
  const uint32_t page_size = BigEndian32(&header[8]);
  const bool power_of_two =
      page_size >= 512 && page_size <= 65536 && (page_size & (page_size - 1)) == 0;
  if ((magic != kMagicLittleEndian && magic != kMagicBigEndian) ||
      BigEndian32(&header[4]) != kFormatVersion || !power_of_two) {
    return scan;
  }
  const bool big_endian = magic == kMagicBigEndian;
  uint32_t s0 = 0;
  uint32_t s1 = 0;
  Checksum(big_endian, header.data(), 24, &s0, &s1);
  if (s0 != BigEndian32(&header[24]) || s1 != BigEndian32(&header[28])) return scan;
  scan.header_valid = true;
  scan.frame_bytes = kFrameHeaderBytes + page_size;
  scan.whole_frames = (scan.bytes - kHeaderBytes) / scan.frame_bytes;
  scan.partial_bytes = (scan.bytes - kHeaderBytes) % scan.frame_bytes;

  std::vector<uint8_t> frame(static_cast<size_t>(scan.frame_bytes));
  int64_t valid_frames = 0;  // frames recovery accepts, committed or not
  for (int64_t n = 1; n <= scan.whole_frames; ++n) {
    if (!wal.read(reinterpret_cast<char*>(frame.data()), scan.frame_bytes)) {
      // The file shrank while being read: what is left counts as cut short.
      scan.partial_bytes = 0;
      scan.whole_frames = n - 1;
      break;
    }
    const bool this_generation = std::equal(&frame[8], &frame[16], &header[16]);
    const bool commit = BigEndian32(&frame[4]) != 0;
    if (scan.stop_frame == 0) {
      bool valid = this_generation && BigEndian32(&frame[0]) != 0;
      if (valid) {
        uint32_t c0 = s0;
        uint32_t c1 = s1;
        Checksum(big_endian, frame.data(), 8, &c0, &c1);
        Checksum(big_endian, frame.data() + kFrameHeaderBytes, page_size, &c0, &c1);
        valid = c0 == BigEndian32(&frame[16]) && c1 == BigEndian32(&frame[20]);
        s0 = c0;
        s1 = c1;
      }
      if (valid) {
        valid_frames = n;
        if (commit) {
          scan.kept_frames = n;
          ++scan.kept_commits;
        }
        continue;
      }
      scan.stop_frame = n;
      scan.stop = this_generation ? WalScan::Stop::kDamagedFrame : WalScan::Stop::kOlderFrame;
    }
    if (this_generation) {
      ++scan.dropped_frames;
      if (commit) ++scan.dropped_commits;
    }
  }
  scan.dropped_frames += valid_frames - scan.kept_frames;  // a transaction without its commit
  scan.writer_committed_frames = WriterCommittedFrames(database_path + "-shm", &header[16]);
  return scan;
}

}  // namespace fleetmap::store::internal
