#include "common/transport/state_messages.hpp"

namespace fleetmap::transport {

const std::string& EntityMessage::entity_id() const {
  return std::visit([](const auto& entity) -> const std::string& { return entity.id; }, entity);
}

const char* SubmapStateName(SubmapState state) {
  switch (state) {
    case SubmapState::kObserved:
      return "observed";
    case SubmapState::kPredicted:
      return "predicted";
    case SubmapState::kConfirmed:
      return "confirmed";
    case SubmapState::kRetracted:
      return "retracted";
  }
  return "unknown";
}

}  // namespace fleetmap::transport
