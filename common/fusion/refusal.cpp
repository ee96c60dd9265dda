#include "common/fusion/refusal.hpp"

namespace fleetmap::fusion {

const char* RefusalName(Refusal refusal) {
  switch (refusal) {
    case Refusal::kMalformed:
      return "malformed";
    case Refusal::kBadRobotId:
      return "bad robot id";
    case Refusal::kTileOutOfRange:
      return "tile out of range";
    case Refusal::kBadTileSettings:
      return "bad tile settings";
    case Refusal::kStampOutOfWindow:
      return "stamp out of window";
    case Refusal::kTileQuota:
      return "tile quota";
    case Refusal::kByteQuota:
      return "byte quota";
    case Refusal::kNotOwner:
      return "not the owner";
    case Refusal::kTooManyIds:
      return "too many ids";
    case Refusal::kUnclaimed:
      return "unclaimed robot id";
    case Refusal::kNotItself:
      return "not its identity";
    case Refusal::kDecodedSize:
      return "decoded size";
    case Refusal::kMemoryBudget:
      return "memory budget";
    case Refusal::kPaintRate:
      return "paint rate";
    case Refusal::kOutsideRegion:
      return "outside the shard's region";
  }
  return "unknown";
}

bool CutsTheMap(Refusal refusal) {
  return refusal == Refusal::kTileQuota || refusal == Refusal::kDecodedSize ||
         refusal == Refusal::kMemoryBudget;
}

}  // namespace fleetmap::fusion
