#pragma once

// One GEOS reentrant context (GEOS_init_r) that owns what it creates: geometries come back as
// owning handles bound to it, and the last error GEOS reported is kept so a failed call can be
// turned into a Status that says why.
//
// Thread-safety: one context per thread (GEOS contexts are not shared); make one per call.

#include <memory>
#include <string>

#include <geos_c.h>

namespace fleetmap::gis {

class GeosContext {
 public:
  struct GeometryDeleter {
    GEOSContextHandle_t handle;
    void operator()(GEOSGeometry* geometry) const { GEOSGeom_destroy_r(handle, geometry); }
  };
  using Geometry = std::unique_ptr<GEOSGeometry, GeometryDeleter>;

  GeosContext();
  ~GeosContext();
  GeosContext(const GeosContext&) = delete;
  GeosContext& operator=(const GeosContext&) = delete;

  GEOSContextHandle_t handle() const { return handle_; }
  // Takes ownership of what a GEOS call returned (null stays null).
  Geometry Own(GEOSGeometry* geometry) const { return Geometry(geometry, {handle_}); }
  // The last error message GEOS gave, or "unknown GEOS error".
  const std::string& last_error() const { return last_error_; }

 private:
  static void OnError(const char* message, void* self);

  GEOSContextHandle_t handle_;
  std::string last_error_ = "unknown GEOS error";
};

}  // namespace fleetmap::gis
