# The fuzz build (FLEETMAP_FUZZ): clang's libFuzzer with AddressSanitizer and
# UndefinedBehaviorSanitizer on every file of the build, so a bug in a library the targets call is
# found where it happens. Any undefined behaviour stops the run (no recovery), as a crash does.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "FLEETMAP_FUZZ needs clang (libFuzzer): configure a build of its own with "
                      "-DCMAKE_CXX_COMPILER=clang++ (`make fuzz` does)")
endif()
set(FLEETMAP_SANITIZE -fsanitize=address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer -g)
# Libraries get libFuzzer's coverage instrumentation without its main().
add_compile_options(${FLEETMAP_SANITIZE} -fsanitize=fuzzer-no-link)
add_link_options(-fsanitize=address,undefined)

# fleetmap_fuzzer(name SOURCES ... DEPS ...): one libFuzzer binary.
function(fleetmap_fuzzer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  fleetmap_program(${name} SOURCES ${ARG_SOURCES} DEPS ${ARG_DEPS})
  target_link_options(${name} PRIVATE -fsanitize=fuzzer)
endfunction()
