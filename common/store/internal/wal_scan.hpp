#pragma once

#include <cstdint>
#include <string>

namespace fleetmap::store::internal {

// What the write-ahead log beside a database holds, read before SQLite opens (and may reset) it,
// and what SQLite's recovery will keep of it. Recovery replays frames in order while each carries
// the header's salts and a valid cumulative checksum, and keeps them up to the last commit frame
// among them; everything after is dropped without a word from SQLite.
// Format: https://www.sqlite.org/fileformat2.html#walformat (big-endian header and frame headers,
// checksums over 32-bit words in the byte order the magic names).
struct WalScan {
  // Why recovery stops reading frames.
  enum class Stop {
    kEnd,           // the end of the file (maybe mid-frame: partial_bytes)
    kOlderFrame,    // a frame of an earlier WAL generation (other salts): already checkpointed
    kDamagedFrame,  // a frame of this generation with a bad checksum or page number
  };

  bool found = false;
  int64_t bytes = 0;
  // Magic, format version, page size and header checksum hold; else SQLite ignores the file.
  bool header_valid = false;
  int64_t frame_bytes = 0;    // 24-byte frame header + one page
  int64_t whole_frames = 0;   // frames the file holds entirely
  int64_t partial_bytes = 0;  // bytes of a last frame cut short (0: the file ends on a frame)

  Stop stop = Stop::kEnd;
  int64_t stop_frame = 0;    // the 1-based frame recovery stops at (0: it read to the end)
  int64_t kept_frames = 0;   // frames 1..kept_frames are replayed
  int64_t kept_commits = 0;  // transactions among them
  // Frames of this generation after kept_frames: a transaction without its commit frame, frames
  // after the stop (their salts say they were written since the WAL was last reset).
  int64_t dropped_frames = 0;
  // Commit frames among them: transactions their writer committed that recovery cannot replay.
  int64_t dropped_commits = 0;
  // From the -shm its last writer left, when it is of this WAL's generation: the frames that
  // writer knew committed (its wal-index mxFrame); -1 when there is no such -shm.
  int64_t writer_committed_frames = -1;

  // Committed frames the writer's -shm counts beyond what recovery keeps (0 when unknown).
  int64_t CommittedFramesLost() const {
    return writer_committed_frames > kept_frames ? writer_committed_frames - kept_frames : 0;
  }
  // The file ends mid-frame after frames of this generation (a frame cut short after older
  // frames belonged to an older, checkpointed generation).
  bool EndsMidFrame() const { return partial_bytes > 0 && stop != Stop::kOlderFrame; }
  // Something of this generation is dropped: recovery will not give back all the file holds.
  bool DropsData() const {
    return header_valid && (dropped_frames > 0 || EndsMidFrame() || CommittedFramesLost() > 0);
  }
  // Bytes of the file recovery drops: whole frames of this generation and a cut-short one.
  int64_t DroppedBytes() const {
    return dropped_frames * frame_bytes + (EndsMidFrame() ? partial_bytes : 0);
  }
};

// Scans "<database_path>-wal" and "<database_path>-shm". Never fails: an unreadable or missing
// file is reported as such in the result.
WalScan ScanWal(const std::string& database_path);

}  // namespace fleetmap::store::internal
