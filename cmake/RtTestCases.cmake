# How rt registers its tests so that a skip cannot hide a failure (tests/CMakeLists.txt;
# tools/tests/test_skips.py registers a small project the same way and checks it).
# ctest counts a test skipped when it exits 77 (SKIP_RETURN_CODE), failed on any other
# non-zero code, whatever it printed.
get_filename_component(RT_SCRIPT_CASE "${CMAKE_CURRENT_LIST_DIR}/../tests/script_case.sh" ABSOLUTE)

# rt_discover_cases(TARGET PREFIX LABEL [ARG...]): each TEST_CASE of a doctest suite is
# one ctest test; a case that skips (RT_SKIP, tests/doctest_main.cpp) exits 77. The ARGs
# go to the suite (--not-done-skips: the library suites).
function(rt_discover_cases target prefix label)
  doctest_discover_tests(${target} TEST_PREFIX "${prefix}" EXTRA_ARGS ${ARGN}
    PROPERTIES LABELS "${label}" SKIP_RETURN_CODE 77 ${rt_emulator_properties}
    WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
endfunction()

# rt_add_script_test(NAME -D... -P CASE.cmake): a cmake -P test case, which exits 0 or 1
# only: tests/script_case.sh turns its rt_skip (tests/skip.cmake) into 77.
find_program(RT_SH sh NO_CMAKE_FIND_ROOT_PATH)
function(rt_add_script_test name)
  set(runner "${CMAKE_COMMAND}")
  if(RT_SH)
    set(runner "${RT_SH}" "${RT_SCRIPT_CASE}" "${CMAKE_COMMAND}" -DRT_SKIPPABLE=ON)
  endif()
  add_test(NAME "${name}" COMMAND ${runner} ${ARGN})
  set_tests_properties("${name}" PROPERTIES SKIP_RETURN_CODE 77)
endfunction()
