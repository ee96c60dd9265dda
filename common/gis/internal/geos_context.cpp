#include "common/gis/internal/geos_context.hpp"

#include "common/core/check.hpp"

namespace fleetmap::gis {

GeosContext::GeosContext() : handle_(GEOS_init_r()) {
  FLEETMAP_CHECK(handle_ != nullptr, "GEOS_init_r failed");
  GEOSContext_setErrorMessageHandler_r(handle_, &GeosContext::OnError, this);
}

GeosContext::~GeosContext() { GEOS_finish_r(handle_); }

void GeosContext::OnError(const char* message, void* self) {
  static_cast<GeosContext*>(self)->last_error_ = message;
}

}  // namespace fleetmap::gis
