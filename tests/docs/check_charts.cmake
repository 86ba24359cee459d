# The README's and the documents' benchmark charts are what scripts/plot_benchmarks.py draws from the
# CSV files the benchmarks wrote (samples/bench/results/vm-2core): redraws them and compares byte for
# byte (test doc_charts). Variables: PYTHON, ROOT (the source tree), OUT (scratch directory).
cmake_minimum_required(VERSION 3.16)
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
execute_process(COMMAND ${PYTHON} ${ROOT}/scripts/plot_benchmarks.py ${ROOT}/samples/bench/results/vm-2core ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "plot_benchmarks.py failed (${rc}):\n${out}${err}")
endif()
set(failures 0)
foreach(chart bench_box2d_scenes.svg bench_queries_pareto.svg)
  file(READ "${OUT}/${chart}" drawn)
  file(READ "${ROOT}/docs/img/${chart}" kept)
  if(NOT drawn STREQUAL kept)
    message(SEND_ERROR "docs/img/${chart} is not what plot_benchmarks.py draws from the kept CSV files; "
                       "redraw it: python3 scripts/plot_benchmarks.py samples/bench/results/vm-2core docs/img")
    math(EXPR failures "${failures} + 1")
  else()
    message(STATUS "${chart}: as drawn from the CSV")
  endif()
endforeach()
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} chart(s) differ")
endif()
