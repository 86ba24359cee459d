# Configures, builds and installs this source tree as shared libraries (BUILD_SHARED_LIBS=ON) in
# RUGO_SCRATCH/build and RUGO_SCRATCH/prefix, with the outer build's compilers, build type, packages and
# options. The tests exported_symbols and consumer_package_shared use the result (CTest fixture
# rugo_shared). Tests and samples are left out: some call librugo's internals, which a shared librugo
# does not export. The build directory is kept between runs, so a rerun rebuilds only what changed.

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
endfunction()

# Lists arrive with | for ; (a ; would split the ctest command line).
string(REPLACE "|" ";" prefix_path "${RUGO_PREFIX_PATH}")
set(package_dirs "")
foreach(var box2d_DIR Eigen3_DIR)
  if(${var})
    list(APPEND package_dirs -D${var}=${${var}})
  endif()
endforeach()
if(RUGO_MAKE_PROGRAM)
  list(APPEND package_dirs -DCMAKE_MAKE_PROGRAM=${RUGO_MAKE_PROGRAM})
endif()

run(${CMAKE_COMMAND} -S ${RUGO_SOURCE_DIR} -B ${RUGO_SCRATCH}/build -G ${RUGO_GENERATOR}
    -DCMAKE_C_COMPILER=${RUGO_C_COMPILER} -DCMAKE_CXX_COMPILER=${RUGO_CXX_COMPILER}
    "-DCMAKE_C_FLAGS=${RUGO_C_FLAGS}" "-DCMAKE_CXX_FLAGS=${RUGO_CXX_FLAGS}"
    -DCMAKE_BUILD_TYPE=${RUGO_BUILD_TYPE} "-DCMAKE_PREFIX_PATH=${prefix_path}" ${package_dirs}
    -DBUILD_SHARED_LIBS=ON -DRUGO_BUILD_TESTS=OFF -DRUGO_BUILD_SAMPLES=OFF -DRUGO_BUILD_FUZZERS=OFF
    -DRUGO_WITH_EIGEN=${RUGO_WITH_EIGEN} -DRUGO_WITH_BOX2D=${RUGO_WITH_BOX2D} -DRUGO_SANITIZE=${RUGO_SANITIZE}
    -DRUGO_WARNINGS_AS_ERRORS=${RUGO_WARNINGS_AS_ERRORS} -DRUGO_ENABLE_ASSERTS=${RUGO_ENABLE_ASSERTS})
# Two jobs unless the caller says otherwise: this runs beside the other tests.
if(NOT DEFINED ENV{CMAKE_BUILD_PARALLEL_LEVEL})
  set(ENV{CMAKE_BUILD_PARALLEL_LEVEL} 2)
endif()
run(${CMAKE_COMMAND} --build ${RUGO_SCRATCH}/build)
file(REMOVE_RECURSE ${RUGO_SCRATCH}/prefix)
run(${CMAKE_COMMAND} --install ${RUGO_SCRATCH}/build --prefix ${RUGO_SCRATCH}/prefix)
message(STATUS "shared build installed in ${RUGO_SCRATCH}/prefix")
