# The pixel story quoted in docs/student-guide.md ("Asking a pixel") is what the
# program prints today: run it, indent it as the page does, and find it there.
#   cmake -DPROGRAM=... -DSCENE=... -DPAGE=... -DCOLUMN=200 -DROW=150 -P doc_story_case.cmake
include("${CMAKE_CURRENT_LIST_DIR}/../skip.cmake")
execute_process(COMMAND "${PROGRAM}" "${SCENE}" --pixel ${COLUMN} ${ROW}
                RESULT_VARIABLE code OUTPUT_VARIABLE story ERROR_VARIABLE errors)
if(code EQUAL 3)
  rt_skip("${errors}")
  return()
endif()
if(NOT code EQUAL 0)
  message(FATAL_ERROR "expected exit 0 from ${PROGRAM} --pixel ${COLUMN} ${ROW}, found ${code}: ${errors}")
endif()
string(REGEX REPLACE "\n$" "" story "${story}")
string(REPLACE "\n" "\n    " indented "    ${story}")
file(READ "${PAGE}" page)
string(FIND "${page}" "${indented}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${PAGE}: expected the story of pixel ${COLUMN} ${ROW} as the program prints it now, "
                      "found another (the page is stale: paste this, indented by 4 spaces):\n${story}")
endif()
message(STATUS "${PAGE}: the quoted story of pixel ${COLUMN} ${ROW} is the program's")
