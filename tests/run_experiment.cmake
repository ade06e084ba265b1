# Runs `talus experiment NAME --quick` into a fresh folder and checks that it
# rendered: a report.md and at least one PNG figure.
# Usage: cmake -DTALUS=... -DNAME=... -DOUT=... -P run_experiment.cmake
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${TALUS}" experiment "${NAME}" --quick --out "${OUT}"
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE error)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "talus experiment ${NAME} failed (${result}):\n${output}\n${error}")
endif()
if(NOT EXISTS "${OUT}/${NAME}/report.md")
  message(FATAL_ERROR "talus experiment ${NAME} wrote no report.md")
endif()
file(GLOB figures "${OUT}/${NAME}/*.png")
list(LENGTH figures count)
if(count EQUAL 0)
  message(FATAL_ERROR "talus experiment ${NAME} rendered no PNG figure")
endif()
message(STATUS "${NAME}: report.md and ${count} figures")
