# Run at build time (cmake -P), by common/config: writes OUTPUT from TEMPLATE with the fleetmap
# version and the git commit SOURCE_DIR was built from, so that `--version` names the commit of
# this build, not of the last cmake run. Outside a git checkout of SOURCE_DIR (a release tarball,
# or a tarball unpacked inside some other repository) the commit is "unknown".
# configure_file rewrites OUTPUT only when its text changes: an unchanged commit rebuilds nothing.
#
# Variables: SOURCE_DIR, FLEETMAP_VERSION, TEMPLATE, OUTPUT.
set(FLEETMAP_GIT_COMMIT "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(
    COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} rev-parse --show-toplevel
    OUTPUT_VARIABLE toplevel OUTPUT_STRIP_TRAILING_WHITESPACE
    RESULT_VARIABLE toplevel_result ERROR_QUIET)
  file(REAL_PATH "${SOURCE_DIR}" source_real)
  if(toplevel_result EQUAL 0)
    file(REAL_PATH "${toplevel}" toplevel_real)
  endif()
  if(toplevel_result EQUAL 0 AND toplevel_real STREQUAL source_real)
    execute_process(
      COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} rev-parse --short=12 HEAD
      OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE
      RESULT_VARIABLE commit_result ERROR_QUIET)
    if(commit_result EQUAL 0 AND NOT commit STREQUAL "")
      set(FLEETMAP_GIT_COMMIT "${commit}")
      # Tracked files changed since the commit: the binary is not exactly that commit.
      execute_process(
        COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} status --porcelain --untracked-files=no
        OUTPUT_VARIABLE changes OUTPUT_STRIP_TRAILING_WHITESPACE
        RESULT_VARIABLE status_result ERROR_QUIET)
      if(status_result EQUAL 0 AND NOT changes STREQUAL "")
        string(APPEND FLEETMAP_GIT_COMMIT "-dirty")
      endif()
    endif()
  endif()
endif()
configure_file(${TEMPLATE} ${OUTPUT} @ONLY)
