#include "common/transport/state_messages.hpp"

namespace fleetmap::transport {

const std::string& EntityMessage::entity_id() const { return scene::EntityId(entity); }

}  // namespace fleetmap::transport
