# Finds the few OpenCV modules fleetmap uses without the full libopencv-dev meta package
# (Debian ships OpenCVConfig.cmake only with it, and it pulls in the whole of OpenCV).
# Creates opencv::<module> imported targets for each requested component.
find_path(OpenCVModules_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
set(OpenCVModules_FOUND TRUE)
foreach(module IN LISTS OpenCVModules_FIND_COMPONENTS)
  find_library(OpenCVModules_${module}_LIBRARY NAMES opencv_${module})
  if(OpenCVModules_${module}_LIBRARY AND OpenCVModules_INCLUDE_DIR)
    set(OpenCVModules_${module}_FOUND TRUE)
    if(NOT TARGET opencv::${module})
      add_library(opencv::${module} UNKNOWN IMPORTED)
      set_target_properties(opencv::${module} PROPERTIES
        IMPORTED_LOCATION "${OpenCVModules_${module}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${OpenCVModules_INCLUDE_DIR}")
    endif()
  else()
    set(OpenCVModules_${module}_FOUND FALSE)
  endif()
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenCVModules
  REQUIRED_VARS OpenCVModules_INCLUDE_DIR HANDLE_COMPONENTS)
