# Fails unless the plugin module LIBRARY exports exactly the ABI's entry point
# (shadowcts_backend_negotiate) among its defined dynamic symbols: a plugin that links the suite's
# static libraries must not export their C++ symbols (examples/plugin_exports.map).
# Run as `cmake -DNM=<nm> -DLIBRARY=<module> -P <this file>`.
cmake_minimum_required(VERSION 3.25)
execute_process(COMMAND ${NM} -D --defined-only ${LIBRARY} OUTPUT_VARIABLE symbols
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${NM} -D --defined-only ${LIBRARY} failed (${status})")
endif()
string(REGEX MATCHALL "[^\n]+" lines "${symbols}")
set(exported "")
foreach(line ${lines})
  string(REGEX REPLACE "^[0-9a-fA-F]* *[A-Za-z] +" "" name "${line}")
  list(APPEND exported ${name})
endforeach()
if(NOT exported STREQUAL "shadowcts_backend_negotiate")
  list(LENGTH exported count)
  message(FATAL_ERROR "${LIBRARY} exports ${count} symbols, not only shadowcts_backend_negotiate: "
                      "${exported}")
endif()
message(STATUS "${LIBRARY}: exports shadowcts_backend_negotiate only")
