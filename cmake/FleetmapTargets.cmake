# The project's target helpers: its warnings, a module library, a program.
# fleetmap_warnings(target): the project's warning set, as errors when FLEETMAP_WERROR is on.
function(fleetmap_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(FLEETMAP_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# fleetmap_library(name SOURCES ... DEPS ...): one module = one library, exported as fleetmap::name.
function(fleetmap_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(fleetmap_${name} ${ARG_SOURCES})
  add_library(fleetmap::${name} ALIAS fleetmap_${name})
  target_include_directories(fleetmap_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(fleetmap_${name} PUBLIC ${ARG_DEPS})
  fleetmap_warnings(fleetmap_${name})
endfunction()

# fleetmap_program(name SOURCES ... DEPS ...): an executable whose includes are spelled from the
# repository root.
function(fleetmap_program name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  fleetmap_warnings(${name})
endfunction()
