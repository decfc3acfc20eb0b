# Fails when a source includes a layer above its own (DESIGN.md, "Layout"): core/ and the public
# headers include nothing above them; the oracles nothing of what they judge; the algorithm
# folders neither the runner nor the oracles. Run as `cmake -DROOT=<source dir> -P <this file>`.
cmake_minimum_required(VERSION 3.25)
set(above_core oracles reference simd gpu runner cli)
set(above_oracles reference simd gpu runner cli)
set(above_algorithms oracles runner cli)
# Algorithm sources that still read an oracle's code (the judge shares it: a known debt, listed
# in docs/specification.md). Nothing may join this list; each entry should leave it.
set(shares_oracle_code
  reference/embree/hard_shadow_embree.cpp
  reference/lightassign/brute_assignment.cpp
  reference/softtile/shadow_cone.cpp
  reference/softtile/softtile_algorithm.h
  reference/softtile/softtile_gather.cpp
)

set(violations "")
function(check_folder folder forbidden)
  file(GLOB_RECURSE sources RELATIVE ${ROOT}
       ${ROOT}/${folder}/*.h ${ROOT}/${folder}/*.cpp ${ROOT}/${folder}/*.cuh ${ROOT}/${folder}/*.cu)
  foreach(source ${sources})
    file(STRINGS ${ROOT}/${source} includes REGEX "^#include \"[a-z_]+/")
    foreach(line ${includes})
      string(REGEX REPLACE "^#include \"([a-z_]+)/.*" "\\1" layer "${line}")
      if(layer IN_LIST forbidden)
        if(layer STREQUAL "oracles" AND source IN_LIST shares_oracle_code)
          continue()
        endif()
        set(violations "${violations}\n  ${source}: ${line}")
      endif()
    endforeach()
  endforeach()
  set(violations "${violations}" PARENT_SCOPE)
endfunction()

check_folder(core "${above_core}")
check_folder(include/shadowcts "${above_core}")
check_folder(oracles "${above_oracles}")
foreach(folder reference simd gpu)
  check_folder(${folder} "${above_algorithms}")
endforeach()
# An entry of the list that no longer includes an oracle must leave it.
foreach(source ${shares_oracle_code})
  file(STRINGS ${ROOT}/${source} includes REGEX "^#include \"oracles/")
  if(NOT includes)
    set(violations "${violations}\n  ${source}: listed as sharing oracle code, but does not")
  endif()
endforeach()

if(violations)
  message(FATAL_ERROR "includes across the layers:${violations}")
endif()
message(STATUS "layers: every include follows them")
