# consume_installed.cmake — builds examples/ against an *installed* frontsteal, as a user would (cmake -P).
#
#   MODE=examples  cmake --install the build into a fresh temporary prefix, then configure, build and run each
#                  example with -DCMAKE_PREFIX_PATH=<prefix>; each must exit 0 (the examples check themselves:
#                  exactly-once rows; the sound ring passes and the planted defect is caught).
#   MODE=negative  the negative control: the same configure against an EMPTY prefix must fail, and fail at
#                  find_package(frontsteal), so the test above cannot pass by finding a frontsteal elsewhere.
# Either way the temporary directory is removed afterwards, on failure too (its logs are printed first).
#
# Inputs (-D): MODE, BUILD_DIR (the configured and built frontsteal), SOURCE_DIR, WORK_ROOT, GENERATOR,
# CXX_COMPILER, CXX_FLAGS, LINKER_FLAGS (so a sanitizer build links its examples the same way), WITH_RELACY.
cmake_minimum_required(VERSION 3.25)

string(RANDOM LENGTH 8 _tag)
set(work ${WORK_ROOT}/consume-${MODE}-${_tag})
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})

function(fail message)
  file(REMOVE_RECURSE ${work})
  message(FATAL_ERROR "${message}")
endfunction()

# Runs a command; on a non-zero exit (unless ALLOW_FAILURE) fails the test with its output. OUT receives the
# exit code, OUTPUT the text.
function(run_step name)
  cmake_parse_arguments(S "ALLOW_FAILURE" "OUT;OUTPUT" "COMMAND" ${ARGN})
  execute_process(COMMAND ${S_COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message(STATUS "${name}: exit ${rc}")
  if(NOT S_ALLOW_FAILURE AND NOT rc EQUAL 0)
    fail("${name} failed (exit ${rc}):\n${out}")
  endif()
  if(S_OUT)
    set(${S_OUT} ${rc} PARENT_SCOPE)
  endif()
  if(S_OUTPUT)
    set(${S_OUTPUT} "${out}" PARENT_SCOPE)
  endif()
endfunction()

# Configure arguments shared by every example: the main build's compiler and flags; the package registry
# off, so only CMAKE_PREFIX_PATH can supply frontsteal.
function(configure_example name prefix)
  cmake_parse_arguments(C "ALLOW_FAILURE" "OUT;OUTPUT" "" ${ARGN})
  set(args -S ${SOURCE_DIR}/examples/${name} -B ${work}/build-${name} -G ${GENERATOR}
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER} "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
      "-DCMAKE_EXE_LINKER_FLAGS=${LINKER_FLAGS}" -DCMAKE_PREFIX_PATH=${prefix}
      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
  if(C_ALLOW_FAILURE)
    run_step("configure ${name}" ALLOW_FAILURE OUT rc OUTPUT text COMMAND ${CMAKE_COMMAND} ${args})
    set(${C_OUT} ${rc} PARENT_SCOPE)
    set(${C_OUTPUT} "${text}" PARENT_SCOPE)
  else()
    run_step("configure ${name}" COMMAND ${CMAKE_COMMAND} ${args})
  endif()
endfunction()

if(MODE STREQUAL "negative")
  file(MAKE_DIRECTORY ${work}/empty-prefix)
  configure_example(own_item_function ${work}/empty-prefix ALLOW_FAILURE OUT rc OUTPUT text)
  if(rc EQUAL 0)
    fail("negative control: own_item_function configured against an empty prefix: a frontsteal was found "
         "outside CMAKE_PREFIX_PATH, so the install test would not show that the install works")
  endif()
  if(NOT text MATCHES "frontsteal-config\\.cmake|frontsteal_DIR")
    fail("negative control: configure failed, but not at find_package(frontsteal):\n${text}")
  endif()
  message(STATUS "negative control: configuring against an empty prefix fails at find_package(frontsteal), as it must")
  file(REMOVE_RECURSE ${work})
  return()
elseif(NOT MODE STREQUAL "examples")
  fail("MODE must be examples or negative, got '${MODE}'")
endif()

set(prefix ${work}/prefix)
run_step("install into ${prefix}" COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
# The export must not carry build-tree paths or the build's private dependencies (Open CASCADE, EGL, ...).
file(GLOB _exports ${prefix}/lib*/cmake/frontsteal/frontsteal-*targets*.cmake)
foreach(_f IN LISTS _exports)
  file(READ ${_f} _text)
  if(_text MATCHES "TK[A-Z][A-Za-z]+|OpenCASCADE|OpenGL|EGL|benchmark::|Catch2")
    fail("${_f} names '${CMAKE_MATCH_0}', which must not reach a consumer")
  endif()
  foreach(_tree ${SOURCE_DIR} ${BUILD_DIR})
    string(FIND "${_text}" "${_tree}" _at)
    if(NOT _at EQUAL -1)
      fail("${_f} names the build machine's ${_tree}")
    endif()
  endforeach()
endforeach()

set(examples own_item_function)
if(WITH_RELACY)
  list(APPEND examples own_lock_free_structure)
endif()
set(own_item_function_args --threads 2 --rows 96 --width 96 --max-iter 200 --frames 5)
set(own_lock_free_structure_args)
foreach(name IN LISTS examples)
  configure_example(${name} ${prefix})
  run_step("build ${name}" COMMAND ${CMAKE_COMMAND} --build ${work}/build-${name})
  run_step("run ${name}" OUTPUT text COMMAND ${work}/build-${name}/${name} ${${name}_args})
  message("${text}")
endforeach()
file(REMOVE_RECURSE ${work})
