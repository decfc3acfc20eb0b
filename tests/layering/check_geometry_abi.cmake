# Fails when a header of the shared host/device geometry (include/shadowcts/geometry/) does not
# wrap its definitions in SHADOWCTS_GEOMETRY_ABI_BEGIN / _END (shadowcts/host_device.h): without
# them, a copy compiled with FMA contraction (the emulated kernels) and one compiled without
# would share symbol names, and the linker would hand one rounding to code written for the other.
# Run as `cmake -DROOT=<source dir> -P <this file>`.
cmake_minimum_required(VERSION 3.25)
file(GLOB headers RELATIVE ${ROOT} ${ROOT}/include/shadowcts/geometry/*.h)
set(missing "")
foreach(header ${headers})
  file(READ ${ROOT}/${header} text)
  string(FIND "${text}" "SHADOWCTS_GEOMETRY_ABI_BEGIN" begin)
  string(FIND "${text}" "SHADOWCTS_GEOMETRY_ABI_END" end)
  if(begin EQUAL -1 OR end EQUAL -1 OR end LESS begin)
    list(APPEND missing ${header})
  endif()
endforeach()
list(LENGTH headers count)
if(count EQUAL 0)
  message(FATAL_ERROR "no header found under ${ROOT}/include/shadowcts/geometry")
endif()
if(missing)
  list(JOIN missing "\n  " text)
  message(FATAL_ERROR "shared geometry without SHADOWCTS_GEOMETRY_ABI_BEGIN/_END:\n  ${text}")
endif()
message(STATUS "${count} shared geometry headers carry the ABI namespace")
