# The shared libraries of the shared_build fixture export exactly the public API:
#  - librugo.so and librugo_fit.so: every exported symbol is a rugo_ function declared in the public
#    headers (include/rugo/*.h; fit.h belongs to librugo_fit.so, the others to librugo.so), none starts
#    with rugo__, and every function the headers declare is exported by its library (a declaration
#    without RUGO_API would be hidden, and programs linking the shared library would not link).
#  - librugo_box2d.so: every exported symbol is in namespace rugo and not one of the bridge's internals
#    (rugo::detail, rugo::Bridge::Impl), apart from the vague-linkage noise described below.
# The declared functions come from the compiler itself: GCC's -aux-info writes the prototype of every
# function a translation unit declares, with the file and line, so no hand-written header parser is
# involved. Inline functions of the headers are static there and not part of any library.
#
# Inputs: RUGO_LIB_DIR (the shared build's directory), RUGO_INCLUDE_DIR, RUGO_NM, RUGO_AUX_INFO_CC (a
# GCC), RUGO_WITH_EIGEN, RUGO_WITH_BOX2D, RUGO_WORK_DIR (scratch).
cmake_policy(VERSION 3.16) # if(IN_LIST)

set(failures "")
macro(fail text)
  string(APPEND failures "  ${text}\n")
endmacro()

# --- Functions declared in the public headers, by library ---------------------------------------------
file(MAKE_DIRECTORY ${RUGO_WORK_DIR})
set(tu "#include <rugo/rugo.h>\n")
if(RUGO_WITH_EIGEN)
  string(APPEND tu "#include <rugo/fit.h>\n")
endif()
file(WRITE ${RUGO_WORK_DIR}/public_headers.c "${tu}")
execute_process(COMMAND ${RUGO_AUX_INFO_CC} -std=c99 -fsyntax-only -aux-info ${RUGO_WORK_DIR}/declared.txt
                        -I${RUGO_INCLUDE_DIR} ${RUGO_WORK_DIR}/public_headers.c
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the public headers do not compile as C99: ${err}")
endif()
file(STRINGS ${RUGO_WORK_DIR}/declared.txt aux_lines)
set(declared_rugo "")
set(declared_fit "")
set(here "/* ${RUGO_INCLUDE_DIR}/rugo/")
string(LENGTH "${here}" here_length)
foreach(line IN LISTS aux_lines)
  # /* <RUGO_INCLUDE_DIR>/rugo/contour.h:63:NC */ extern rugo_real rugo_contour_signed_area (rugo_contour);
  string(FIND "${line}" "${here}" at)
  if(NOT at EQUAL 0)
    continue() # a system header's function
  endif()
  string(SUBSTRING "${line}" ${here_length} -1 rest)
  if(rest MATCHES "^([a-z0-9_]+\\.h):[0-9]+:[A-Z]+ \\*/ extern [^(]*[ *]([A-Za-z_][A-Za-z0-9_]*) \\(")
    if(CMAKE_MATCH_1 STREQUAL "fit.h")
      list(APPEND declared_fit ${CMAKE_MATCH_2})
    else()
      list(APPEND declared_rugo ${CMAKE_MATCH_2})
    endif()
  endif()
endforeach()
list(LENGTH declared_rugo n_rugo)
if(n_rugo LESS 100)
  message(FATAL_ERROR "found only ${n_rugo} declarations in the public headers: has -aux-info's format changed?")
endif()

# exported(LIB VAR): "TYPE NAME" of every defined dynamic symbol of LIB (demangled), in VAR.
function(exported lib var)
  execute_process(COMMAND ${RUGO_NM} -D -C --defined-only ${lib} OUTPUT_VARIABLE out RESULT_VARIABLE rc
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${RUGO_NM} failed on ${lib}: ${err}")
  endif()
  string(REPLACE ";" "\\;" out "${out}")
  string(REPLACE "\n" ";" lines "${out}")
  set(result "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[0-9a-fA-F]+ ([A-Za-z]) (.*)$")
      list(APPEND result "${CMAKE_MATCH_1} ${CMAKE_MATCH_2}")
    endif()
  endforeach()
  set(${var} "${result}" PARENT_SCOPE)
endfunction()

# --- The C libraries ------------------------------------------------------------------------------------
set(report "")
foreach(name rugo fit)
  if(name STREQUAL "fit" AND NOT RUGO_WITH_EIGEN)
    continue()
  endif()
  if(name STREQUAL "rugo")
    set(lib ${RUGO_LIB_DIR}/librugo.so)
  else()
    set(lib ${RUGO_LIB_DIR}/librugo_fit.so)
  endif()
  set(declared ${declared_${name}})
  exported(${lib} symbols)
  set(names "")
  foreach(sym IN LISTS symbols)
    string(SUBSTRING "${sym}" 2 -1 symbol)
    list(APPEND names "${symbol}")
    if(symbol MATCHES "^rugo__")
      fail("${lib}: exports the internal ${symbol}")
    elseif(NOT symbol MATCHES "^rugo_")
      fail("${lib}: exports ${symbol}, not a rugo_ name")
    elseif(NOT symbol IN_LIST declared)
      fail("${lib}: exports ${symbol}, which no public header of this library declares")
    endif()
  endforeach()
  foreach(symbol IN LISTS declared)
    if(NOT symbol IN_LIST names)
      fail("${lib}: does not export ${symbol}, declared in the public headers (RUGO_API missing?)")
    endif()
  endforeach()
  list(LENGTH names n)
  list(LENGTH declared nd)
  string(APPEND report "${lib}: ${n} exported symbols, ${nd} functions declared for it\n")
endforeach()

# --- The Box2D bridge -----------------------------------------------------------------------------------
# Besides its own names, a C++ shared library defines weak (vague-linkage) copies of code and data that
# every object using them emits and the dynamic linker merges across libraries: out-of-line members of
# standard-library templates instantiated on types with default visibility (std::vector<int>::
# _M_realloc_insert; the standard library declares namespace std with default visibility, and such
# members are not inline, so -fvisibility-inlines-hidden leaves them alone), and the typeinfo of
# Box2D's polymorphic classes, which Box2D's own headers mark default (B2_API) so that RTTI agrees
# across libraries. They are not the bridge's API and hiding them could break that merging, so weak
# symbols (nm types V, W, u, v, w) that name nothing of rugo are counted as noise. A weak symbol that
# names a rugo type is checked like any other.
if(RUGO_WITH_BOX2D)
  set(lib ${RUGO_LIB_DIR}/librugo_box2d.so)
  exported(${lib} symbols)
  set(own 0)
  set(noise 0)
  foreach(sym IN LISTS symbols)
    string(SUBSTRING "${sym}" 0 1 type)
    string(SUBSTRING "${sym}" 2 -1 symbol)
    if(type MATCHES "^[VWuvw]$" AND NOT symbol MATCHES "rugo")
      math(EXPR noise "${noise} + 1")
      continue()
    endif()
    # Special members of a class (typeinfo, vtable, thunks) are named after it.
    string(REGEX REPLACE "^(typeinfo for |typeinfo name for |vtable for |VTT for |non-virtual thunk to |virtual thunk to )" ""
           name "${symbol}")
    if(NOT name MATCHES "^rugo::")
      fail("${lib}: exports ${symbol}, not in namespace rugo")
    elseif(name MATCHES "^rugo::detail::|^rugo::Bridge::Impl($|::| )")
      fail("${lib}: exports the internal ${symbol}")
    else()
      math(EXPR own "${own} + 1")
    endif()
  endforeach()
  if(NOT "T rugo::Bridge::Step(float, int, int)" IN_LIST symbols)
    fail("${lib}: does not export rugo::Bridge::Step (RUGO_API missing on the class?)")
  endif()
  string(APPEND report "${lib}: ${own} exported rugo:: symbols, ${noise} weak standard-library and Box2D symbols\n")
endif()

message(STATUS "\n${report}")
if(failures)
  message(FATAL_ERROR "the shared libraries export other than the public API:\n${failures}")
endif()
