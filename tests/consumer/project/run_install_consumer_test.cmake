# CTest driver for InstallConsumer.BuildsAgainstInstalledPackage (registered in
# tests/consumer/CMakeLists.txt). Not part of the consumer project's build.
#
# cmake -DTALUS_BUILD_DIR=... -DCONSUMER_SOURCE_DIR=... -DINSTALL_PREFIX=...
#       -DCONSUMER_BUILD_DIR=... -DCONFIG=... -DGENERATOR=... -DCXX_COMPILER=...
#       -DREADME=... -DEXAMPLES_SOURCE_DIR=... [-DMAKE_PROGRAM=...] [-DEXTRA_CXX_FLAGS=...]
#       -P run_install_consumer_test.cmake
#
# (a) installs the Talus build tree into a fresh prefix, (b) checks that the
# README's "Use it from C++" program is examples/plan.cpp, (c) configures the
# consumer project and the examples/ project against that prefix only,
# (d) builds both, (e) runs the consumer and every example on the installed
# West Bijou DEM and rover.yaml.
cmake_minimum_required(VERSION 3.25)

foreach(var TALUS_BUILD_DIR CONSUMER_SOURCE_DIR INSTALL_PREFIX CONSUMER_BUILD_DIR GENERATOR README
            EXAMPLES_SOURCE_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_install_consumer_test.cmake: ${var} is not set")
  endif()
endforeach()

function(run_step name)
  message(STATUS "---- ${name}: ${ARGN}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rv)
  if(NOT rv EQUAL 0)
    message(FATAL_ERROR "InstallConsumer: step '${name}' failed (${rv}): ${ARGN}")
  endif()
endfunction()

# Start clean each run.
set(EXAMPLES_BUILD_DIR "${CONSUMER_BUILD_DIR}-examples")
file(REMOVE_RECURSE "${INSTALL_PREFIX}" "${CONSUMER_BUILD_DIR}" "${EXAMPLES_BUILD_DIR}")

set(config_args)
if(CONFIG)
  set(config_args --config ${CONFIG})
endif()

# (a) install
run_step(install ${CMAKE_COMMAND} --install ${TALUS_BUILD_DIR} --prefix ${INSTALL_PREFIX} ${config_args})
file(GLOB_RECURSE talus_config "${INSTALL_PREFIX}/*/talusConfig.cmake")
if(NOT talus_config)
  message(FATAL_ERROR "InstallConsumer: no talusConfig.cmake under ${INSTALL_PREFIX} after install")
endif()

# (b) The README's "Use it from C++" program (between the consumer-example markers, without
# the ```cpp fence) is examples/plan.cpp, character for character.
file(READ "${README}" readme)
string(REGEX MATCH "<!-- consumer-example:begin -->\n```cpp\n(.*)```\n<!-- consumer-example:end -->"
       example_block "${readme}")
if(NOT CMAKE_MATCH_1)
  message(FATAL_ERROR "InstallConsumer: no consumer-example block in ${README}")
endif()
file(READ "${EXAMPLES_SOURCE_DIR}/plan.cpp" example_file)
if(NOT CMAKE_MATCH_1 STREQUAL example_file)
  message(FATAL_ERROR "InstallConsumer: the README's C++ program differs from examples/plan.cpp")
endif()

# (c) configure, seeing only the fresh prefix (no package registries)
set(configure_args
  -G ${GENERATOR}
  -DCMAKE_PREFIX_PATH=${INSTALL_PREFIX}
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
  -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
if(CONFIG)
  list(APPEND configure_args -DCMAKE_BUILD_TYPE=${CONFIG})
endif()
if(CXX_COMPILER)
  list(APPEND configure_args -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
if(MAKE_PROGRAM)
  list(APPEND configure_args -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
if(EXTRA_CXX_FLAGS)
  # e.g. the sanitizer flags: an instrumented static libtalus_core needs the
  # sanitizer runtime in the final link.
  list(APPEND configure_args "-DCMAKE_CXX_FLAGS=${EXTRA_CXX_FLAGS}"
                             "-DCMAKE_EXE_LINKER_FLAGS=${EXTRA_CXX_FLAGS}")
endif()
run_step(configure ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${CONSUMER_BUILD_DIR} ${configure_args})
run_step(configure-examples ${CMAKE_COMMAND} -S ${EXAMPLES_SOURCE_DIR} -B ${EXAMPLES_BUILD_DIR}
         ${configure_args})

# The consumer must have found *this* install, not some other talus.
file(STRINGS "${CONSUMER_BUILD_DIR}/CMakeCache.txt" talus_dir_line REGEX "^talus_DIR:")
string(REGEX REPLACE "^talus_DIR:[A-Z]+=" "" talus_dir "${talus_dir_line}")
file(REAL_PATH "${INSTALL_PREFIX}" prefix_real)
if(talus_dir)
  file(REAL_PATH "${talus_dir}" talus_dir)
endif()
string(FIND "${talus_dir}/" "${prefix_real}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "InstallConsumer: consumer found talus in '${talus_dir}', not under ${prefix_real}")
endif()

# (d) build
run_step(build ${CMAKE_COMMAND} --build ${CONSUMER_BUILD_DIR} ${config_args})
run_step(build-examples ${CMAKE_COMMAND} --build ${EXAMPLES_BUILD_DIR} ${config_args})

# (e) run
set(exe "")
foreach(candidate "${CONSUMER_BUILD_DIR}/talus_consumer" "${CONSUMER_BUILD_DIR}/${CONFIG}/talus_consumer")
  if(EXISTS "${candidate}" AND NOT IS_DIRECTORY "${candidate}")
    set(exe "${candidate}")
    break()
  endif()
endforeach()
if(NOT exe)
  message(FATAL_ERROR "InstallConsumer: talus_consumer executable not found in ${CONSUMER_BUILD_DIR}")
endif()
run_step(run ${exe})

# The README's program plans on the installed data and prints its brief report.
set(data "${INSTALL_PREFIX}/share/talus/data")
set(dem "${data}/terrain/west_bijou_escarpment_nasadem25m.asc")
set(rover "${data}/vehicles/rover.yaml")
execute_process(COMMAND "${EXAMPLES_BUILD_DIR}/plan" "${dem}" "${rover}"
                RESULT_VARIABLE rv OUTPUT_VARIABLE report)
message(STATUS "---- examples/plan:\n${report}")
if(NOT rv EQUAL 0)
  message(FATAL_ERROR "InstallConsumer: examples/plan exited ${rv}")
endif()
if(NOT report MATCHES "Talus plan: ok" OR NOT report MATCHES "best: candidate [0-9]+, travel time [0-9.]+ s")
  message(FATAL_ERROR "InstallConsumer: examples/plan printed no successful plan")
endif()
# The same plan under a budget far too small for it: status time_limit, not a hang or a crash
# (exit 0 with the best trajectory so far, or 2 when the global stage had no route yet).
execute_process(COMMAND "${EXAMPLES_BUILD_DIR}/plan_within_budget" "${dem}" "${rover}" 0.001
                RESULT_VARIABLE rv OUTPUT_VARIABLE report)
message(STATUS "---- examples/plan_within_budget 0.001 s:\n${report}")
if(NOT (rv EQUAL 0 OR rv EQUAL 2) OR NOT report MATCHES "status: time_limit")
  message(FATAL_ERROR "InstallConsumer: plan_within_budget with 1 ms did not stop on its budget (${rv})")
endif()
# A budget that is no number is bad input: exit 1.
execute_process(COMMAND "${EXAMPLES_BUILD_DIR}/plan_within_budget" "${dem}" "${rover}" -1
                RESULT_VARIABLE rv OUTPUT_QUIET ERROR_QUIET)
if(NOT rv EQUAL 1)
  message(FATAL_ERROR "InstallConsumer: plan_within_budget -1 exited ${rv}, not 1")
endif()
message(STATUS "InstallConsumer: OK")
