# Builds and runs the consumer project against an installed librugo twice: once through
# find_package(rugo), once through pkg-config. With RUGO_WITH_BOX2D, both ways also build and run the
# Box2D bridge consumer (rugo::box2d, rugo-box2d.pc). The programs check the version macros against the
# package's version.
#
# The installed tree: with RUGO_BUILD_DIR, that build installed into a scratch prefix (the static
# libraries of the test build); with RUGO_PREFIX, a tree installed already (the shared libraries of the
# shared_build fixture). RUGO_LINKAGE (static or shared) says which it is, and every program is checked
# to depend on librugo's shared library exactly when it is shared (RUGO_READELF reads that).
file(REMOVE_RECURSE ${RUGO_SCRATCH})
if(RUGO_PREFIX)
  set(prefix ${RUGO_PREFIX})
else()
  set(prefix ${RUGO_SCRATCH}/prefix)
endif()
if(NOT RUGO_LINKAGE MATCHES "^(static|shared)$")
  message(FATAL_ERROR "RUGO_LINKAGE must be static or shared, not '${RUGO_LINKAGE}'")
endif()

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

if(NOT RUGO_PREFIX)
  run(${CMAKE_COMMAND} --install ${RUGO_BUILD_DIR} --prefix ${prefix})
endif()

# check_linkage(PROGRAM LIBRARY): PROGRAM needs libLIBRARY.so at run time exactly when the linkage is
# shared (a static build installs no .so, a shared one no .a, so this checks what was linked).
function(check_linkage program library)
  execute_process(COMMAND ${RUGO_READELF} -d ${program} OUTPUT_VARIABLE dyn RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${RUGO_READELF} -d ${program} failed")
  endif()
  if(dyn MATCHES "NEEDED[^\n]*\\[lib${library}\\.so")
    set(needed shared)
  else()
    set(needed static)
  endif()
  if(NOT needed STREQUAL RUGO_LINKAGE)
    message(FATAL_ERROR "${program} links lib${library} ${needed}, expected ${RUGO_LINKAGE}:\n${dyn}")
  endif()
endfunction()

set(san_flags "")
if(RUGO_SANITIZE)
  set(san_flags "-fsanitize=address,undefined")
endif()

# 1. CMake package.
run(${CMAKE_COMMAND} -S ${RUGO_CONSUMER_SOURCE} -B ${RUGO_SCRATCH}/build
    -DCMAKE_PREFIX_PATH=${prefix} -DRUGO_WITH_EIGEN=${RUGO_WITH_EIGEN} -DRUGO_WITH_BOX2D=${RUGO_WITH_BOX2D}
    "-DCMAKE_C_FLAGS=${san_flags}" "-DCMAKE_CXX_FLAGS=${san_flags}" "-DCMAKE_EXE_LINKER_FLAGS=${san_flags}")
run(${CMAKE_COMMAND} --build ${RUGO_SCRATCH}/build)
run(${RUGO_SCRATCH}/build/consumer)
check_linkage(${RUGO_SCRATCH}/build/consumer rugo)
if(RUGO_WITH_EIGEN)
  check_linkage(${RUGO_SCRATCH}/build/consumer rugo_fit)
endif()
if(RUGO_WITH_BOX2D)
  run(${RUGO_SCRATCH}/build/consumer_box2d)
  check_linkage(${RUGO_SCRATCH}/build/consumer_box2d rugo_box2d)
endif()

# 2. pkg-config, plain compiler command line.
find_program(PKG_CONFIG pkg-config REQUIRED)
find_program(CC_EXE NAMES cc gcc REQUIRED)
set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig:${prefix}/lib64/pkgconfig")
file(GLOB pcdirs "${prefix}/lib/*/pkgconfig")
foreach(d ${pcdirs})
  set(ENV{PKG_CONFIG_PATH} "${d}:$ENV{PKG_CONFIG_PATH}")
endforeach()
# pkg_flags(MODULE VAR): the --cflags --libs of MODULE as a list; its --modversion in VAR_version.
function(pkg_flags module var)
  execute_process(COMMAND ${PKG_CONFIG} --cflags --libs ${module} OUTPUT_VARIABLE pc RESULT_VARIABLE rc
                  ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pkg-config does not find ${module}: ${err}")
  endif()
  execute_process(COMMAND ${PKG_CONFIG} --modversion ${module} OUTPUT_VARIABLE version
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  separate_arguments(list UNIX_COMMAND "${pc}")
  set(${var} ${list} PARENT_SCOPE)
  set(${var}_version ${version} PARENT_SCOPE)
endfunction()
separate_arguments(san_list UNIX_COMMAND "${san_flags}")
# A shared librugo is found at run time through the programs' run path, as a user's build outside the
# system's library directories would find it.
set(rpath_list "")
if(RUGO_LINKAGE STREQUAL "shared")
  execute_process(COMMAND ${PKG_CONFIG} --variable=libdir rugo OUTPUT_VARIABLE libdir
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(rpath_list "-Wl,-rpath,${libdir}")
endif()
pkg_flags(rugo pc_list)
run(${CC_EXE} -std=c99 ${san_list} "-DRUGO_EXPECTED_VERSION=\"${pc_list_version}\"" ${RUGO_CONSUMER_SOURCE}/consumer.c
    ${pc_list} ${rpath_list} -o ${RUGO_SCRATCH}/consumer_pc)
run(${RUGO_SCRATCH}/consumer_pc)
check_linkage(${RUGO_SCRATCH}/consumer_pc rugo)
if(RUGO_WITH_EIGEN)
  # The import and fit shim through rugo-fit.pc (Requires: rugo), linked by the C compiler.
  pkg_flags(rugo-fit pc_fit_list)
  run(${CC_EXE} -std=c99 ${san_list} ${RUGO_CONSUMER_SOURCE}/consumer_fit.c ${pc_fit_list} ${rpath_list}
      -o ${RUGO_SCRATCH}/consumer_fit_pc)
  run(${RUGO_SCRATCH}/consumer_fit_pc)
  check_linkage(${RUGO_SCRATCH}/consumer_fit_pc rugo_fit)
endif()
if(RUGO_WITH_BOX2D)
  # The bridge through rugo-box2d.pc (Requires: rugo, box2d), linked by the C++ compiler.
  find_program(CXX_EXE NAMES c++ g++ REQUIRED)
  pkg_flags(rugo-box2d pc_b2_list)
  run(${CXX_EXE} -std=c++17 ${san_list} "-DRUGO_EXPECTED_VERSION=\"${pc_b2_list_version}\""
      ${RUGO_CONSUMER_SOURCE}/consumer_box2d.cpp ${pc_b2_list} ${rpath_list} -o ${RUGO_SCRATCH}/consumer_box2d_pc)
  run(${RUGO_SCRATCH}/consumer_box2d_pc)
  check_linkage(${RUGO_SCRATCH}/consumer_box2d_pc rugo_box2d)
endif()
