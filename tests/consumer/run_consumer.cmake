# Installs the rugo build in RUGO_BUILD_DIR into a scratch prefix, then builds and runs the consumer
# project against it twice: once through find_package(rugo), once through pkg-config.
file(REMOVE_RECURSE ${RUGO_SCRATCH})
set(prefix ${RUGO_SCRATCH}/prefix)

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

run(${CMAKE_COMMAND} --install ${RUGO_BUILD_DIR} --prefix ${prefix})

set(san_flags "")
if(RUGO_SANITIZE)
  set(san_flags "-fsanitize=address,undefined")
endif()

# 1. CMake package.
run(${CMAKE_COMMAND} -S ${RUGO_CONSUMER_SOURCE} -B ${RUGO_SCRATCH}/build
    -DCMAKE_PREFIX_PATH=${prefix} -DRUGO_WITH_EIGEN=${RUGO_WITH_EIGEN}
    "-DCMAKE_C_FLAGS=${san_flags}" "-DCMAKE_CXX_FLAGS=${san_flags}" "-DCMAKE_EXE_LINKER_FLAGS=${san_flags}")
run(${CMAKE_COMMAND} --build ${RUGO_SCRATCH}/build)
run(${RUGO_SCRATCH}/build/consumer)

# 2. pkg-config, plain compiler command line.
find_program(PKG_CONFIG pkg-config REQUIRED)
find_program(CC_EXE NAMES cc gcc REQUIRED)
set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig:${prefix}/lib64/pkgconfig")
file(GLOB pcdirs "${prefix}/lib/*/pkgconfig")
foreach(d ${pcdirs})
  set(ENV{PKG_CONFIG_PATH} "${d}:$ENV{PKG_CONFIG_PATH}")
endforeach()
execute_process(COMMAND ${PKG_CONFIG} --cflags --libs rugo OUTPUT_VARIABLE pc RESULT_VARIABLE rc
                OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config does not find rugo")
endif()
separate_arguments(pc_list UNIX_COMMAND "${pc}")
separate_arguments(san_list UNIX_COMMAND "${san_flags}")
run(${CC_EXE} -std=c99 ${san_list} ${RUGO_CONSUMER_SOURCE}/consumer.c ${pc_list} -o ${RUGO_SCRATCH}/consumer_pc)
run(${RUGO_SCRATCH}/consumer_pc)
