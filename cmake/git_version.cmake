# Run at every build (cmake -P): writes OUTPUT from INPUT with the tree's `git describe`, touching
# OUTPUT only when the text changes, so that an unchanged tree rebuilds nothing.
execute_process(COMMAND git describe --always --dirty --tags
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE RUPTURE_GIT_DESCRIBE OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET)
if(NOT RUPTURE_GIT_DESCRIBE)
  set(RUPTURE_GIT_DESCRIBE "unknown")
endif()
configure_file(${INPUT} ${OUTPUT} @ONLY)
