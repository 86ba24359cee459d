# Compiles and runs the complete programs of the documentation (test doc_examples).
#
# An example is a fenced code block right after a marker line:
#     <!-- example: NAME -->
#     ```c            (or ```cpp for the Box2D bridge, ```sh for a session with the rugo tool)
#     ... a whole program with main() ...
#     ```
# Blocks without the marker are fragments and are left alone. Each example is written to
# OUT/NAME.c(pp), compiled with the project's warning flags against the build tree's headers and
# libraries, and run in its own empty directory OUT/NAME/; it must exit with 0 (examples check their
# own results). A shell example runs under `sh -e` with the rugo tool on PATH. Every document given
# must hold at least one example, and names must be unique.
#
# Variables (-D): DOCS (documents, separated by |), OUT, CC, CXX, INCLUDE (include/ of the source tree),
# LIB_RUGO, LIB_BOX2D_BRIDGE and LIB_BOX2D (empty without the bridge), BOX2D_INCLUDE (| separated),
# RUGO_CLI (the rugo tool; empty without the tools), WARNINGS (| separated), SANITIZE (ON/OFF), DATA
# (tests/data, given to shell examples as $RUGO_TEST_DATA). Examples run in document order, so a later
# one may read what an earlier one wrote in its directory (../NAME/).

cmake_minimum_required(VERSION 3.16)
foreach(v DOCS OUT CC INCLUDE LIB_RUGO)
  if(NOT DEFINED ${v} OR "${${v}}" STREQUAL "")
    message(FATAL_ERROR "run_doc_examples.cmake: -D${v}=... is required")
  endif()
endforeach()
string(REPLACE "|" ";" docs "${DOCS}")
string(REPLACE "|" ";" warnings "${WARNINGS}")
string(REPLACE "|" ";" box2d_include "${BOX2D_INCLUDE}")
set(san "")
if(SANITIZE)
  set(san -fsanitize=address,undefined -fno-sanitize-recover=all)
endif()
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")

# rpath for shared builds (harmless for static archives).
set(rpath "")
foreach(lib "${LIB_RUGO}" "${LIB_BOX2D_BRIDGE}" "${LIB_BOX2D}")
  if(NOT lib STREQUAL "")
    get_filename_component(dir "${lib}" DIRECTORY)
    list(APPEND rpath "-Wl,-rpath,${dir}")
  endif()
endforeach()

set(names "")
set(failures 0)
set(marker "<!-- example: ")
foreach(doc ${docs})
  file(READ "${doc}" text)
  get_filename_component(doc_name "${doc}" NAME)
  set(found 0)
  # Scan with string(FIND) on the remaining text: the code is never turned into a CMake list, so its
  # semicolons and brackets need no escaping.
  while(TRUE)
    string(FIND "${text}" "${marker}" at)
    if(at EQUAL -1)
      break()
    endif()
    string(LENGTH "${marker}" mlen)
    math(EXPR at "${at} + ${mlen}")
    string(SUBSTRING "${text}" ${at} -1 text)
    string(FIND "${text}" " -->" end)
    string(SUBSTRING "${text}" 0 ${end} name)
    if(NOT name MATCHES "^[A-Za-z0-9_]+$")
      message(FATAL_ERROR "${doc_name}: bad example name '${name}'")
    endif()
    if(name IN_LIST names)
      message(FATAL_ERROR "${doc_name}: example name '${name}' used twice")
    endif()
    list(APPEND names ${name})
    # The fence must open on the next line.
    string(SUBSTRING "${text}" ${end} -1 text)
    if(NOT text MATCHES "^ -->\n```(c|cpp|sh)\n")
      message(FATAL_ERROR "${doc_name}: example '${name}' is not followed by a ```c, ```cpp or ```sh block")
    endif()
    set(lang ${CMAKE_MATCH_1})
    string(LENGTH " -->\n```${lang}\n" skip)
    string(SUBSTRING "${text}" ${skip} -1 text)
    string(FIND "${text}" "\n```" close)
    if(close EQUAL -1)
      message(FATAL_ERROR "${doc_name}: example '${name}' has no closing fence")
    endif()
    math(EXPR close "${close} + 1")
    string(SUBSTRING "${text}" 0 ${close} code)
    string(SUBSTRING "${text}" ${close} -1 text)
    math(EXPR found "${found} + 1")

    set(src "${OUT}/${name}.${lang}")
    set(exe "${OUT}/${name}.bin")
    file(WRITE "${src}" "${code}")
    set(run_cmd ${exe})
    if(lang STREQUAL "sh")
      if("${RUGO_CLI}" STREQUAL "")
        message(STATUS "${doc_name}: ${name}: skipped (built without the rugo tool)")
        continue()
      endif()
      get_filename_component(cli_dir "${RUGO_CLI}" DIRECTORY)
      set(cmd ${CMAKE_COMMAND} -E true)
      set(run_cmd ${CMAKE_COMMAND} -E env "PATH=${cli_dir}:$ENV{PATH}" "RUGO_TEST_DATA=${DATA}" sh -e ${src})
    elseif(lang STREQUAL "c")
      set(cmd ${CC} -std=c99 ${warnings} ${san} -I${INCLUDE} ${src} -o ${exe} ${LIB_RUGO} -lm ${rpath})
    else()
      if("${LIB_BOX2D_BRIDGE}" STREQUAL "")
        message(STATUS "${doc_name}: ${name}: skipped (built without the Box2D bridge)")
        continue()
      endif()
      set(inc "")
      foreach(d ${box2d_include})
        list(APPEND inc -I${d})
      endforeach()
      set(cmd ${CXX} -std=c++17 ${warnings} ${san} -I${INCLUDE} ${inc} ${src} -o ${exe} ${LIB_BOX2D_BRIDGE}
          ${LIB_RUGO} ${LIB_BOX2D} -lm ${rpath})
    endif()
    execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(SEND_ERROR "${doc_name}: example '${name}' does not compile:\n${out}${err}")
      math(EXPR failures "${failures} + 1")
      continue()
    endif()
    file(MAKE_DIRECTORY "${OUT}/${name}")
    execute_process(COMMAND ${run_cmd} WORKING_DIRECTORY "${OUT}/${name}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                    ERROR_VARIABLE err TIMEOUT 120)
    if(NOT rc EQUAL 0)
      message(SEND_ERROR "${doc_name}: example '${name}' failed (exit ${rc}):\n${out}${err}")
      math(EXPR failures "${failures} + 1")
    else()
      message(STATUS "${doc_name}: ${name}: ok\n${out}")
    endif()
  endwhile()
  if(found EQUAL 0)
    message(SEND_ERROR "${doc_name}: no example found (mark complete programs with <!-- example: NAME -->)")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
list(LENGTH names count)
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} of the documentation examples failed")
endif()
message(STATUS "all ${count} documentation examples compiled and ran")
