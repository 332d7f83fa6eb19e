# rt_skip(REASON), then return(): ends a cmake -P test case as skipped, with its
# reason. cmake -P exits 0 or 1 only, so tests/CMakeLists.txt runs these cases
# through tests/script_case.sh (RT_SKIPPABLE), which turns the line this prints
# into ctest's skip code; without it the case fails, saying why.
function(rt_skip reason)
  if(NOT RT_SKIPPABLE)
    message(FATAL_ERROR "not judged here, and with no sh to run tests/script_case.sh this cannot "
                        "be counted as skipped: ${reason}")
  endif()
  message("SKIPPED: ${reason}")
endfunction()
