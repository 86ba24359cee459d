cmake_minimum_required(VERSION 3.16)
# The layering test: a librugo source may include the private headers of its own layer and of the
# layers below it, never of a layer above (docs/design.md, "Layout"). Public headers (include/rugo)
# and the Box2D bridge include no private header of librugo at all.
#   cmake -DROOT=<source dir> -P check_layering.cmake
# Fails with one line per offending #include.

# Which layers' private headers each layer may include: its own and those it builds on, in data-flow
# order (authoring in io and fit reads text and fits outlines on top of core; geometry goes core ->
# curve -> rough -> shape -> query -> sim). io also reads rough's private header: the shape-file and
# CSV readers report a bad roughness range or profile sample with the very checks the resampling in
# rough applies (rough/internal.h), so that what the readers accept is what the resampling accepts.
set(allowed_core  core)
set(allowed_curve core curve)
set(allowed_rough core curve rough)
set(allowed_shape core curve rough shape)
set(allowed_query core curve rough shape query)
set(allowed_sim   core curve rough shape query sim)
set(allowed_io    core curve rough io)
set(allowed_fit   core curve fit)
set(layers core curve rough shape query sim io fit)

set(problems "")
file(GLOB_RECURSE sources RELATIVE "${ROOT}/librugo" "${ROOT}/librugo/*.c" "${ROOT}/librugo/*.h" "${ROOT}/librugo/*.cpp")
foreach(src ${sources})
  string(REGEX MATCH "^[^/]+" layer "${src}")
  if(NOT layer IN_LIST layers OR src STREQUAL layer)
    string(APPEND problems "librugo/${src}: not in a layer folder (${layers})\n")
    continue()
  endif()
  file(STRINGS "${ROOT}/librugo/${src}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line ${includes})
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*" "\\1" header "${line}")
    if(header MATCHES "^rugo/")
      continue() # public headers may be used from anywhere
    endif()
    if(NOT header MATCHES "^([a-z]+)/")
      string(APPEND problems "librugo/${src}: includes \"${header}\" without its layer (write \"<layer>/${header}\")\n")
      continue()
    endif()
    set(target "${CMAKE_MATCH_1}")
    if(NOT target IN_LIST allowed_${layer})
      string(APPEND problems "librugo/${src}: layer ${layer} includes \"${header}\" of layer ${target} (allowed: ${allowed_${layer}})\n")
    endif()
  endforeach()
endforeach()

# Public headers and the bridge see only the public API.
file(GLOB_RECURSE public RELATIVE "${ROOT}" "${ROOT}/include/*.h" "${ROOT}/include/*.hpp" "${ROOT}/box2d_bridge/*.cpp"
     "${ROOT}/box2d_bridge/*.hpp")
foreach(src ${public})
  file(STRINGS "${ROOT}/${src}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line ${includes})
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*" "\\1" header "${line}")
    foreach(layer ${layers})
      if(header MATCHES "^${layer}/")
        string(APPEND problems "${src}: includes librugo's private \"${header}\"\n")
      endif()
    endforeach()
  endforeach()
endforeach()

list(LENGTH sources nsources)
if(problems)
  message(FATAL_ERROR "layering broken:\n${problems}")
endif()
message(STATUS "layering holds for ${nsources} librugo files")
