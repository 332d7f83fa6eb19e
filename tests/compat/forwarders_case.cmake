# tests/compat/forwarders_case.cmake - the old flat header paths still work, for one release,
# and each one says where its header went.
#
#   cmake -DCXX=... -DFLAGS=... -DINCLUDES=a|b|c -DSOURCE=<repo> -DWORK=<dir> -P forwarders_case.cmake
#
# For every compat/rt/NAME.hpp:
#   - its #warning reads "<rt/NAME.hpp> is deprecated: include <rt/F/NAME.hpp> ..." and each
#     header it names exists under include/rt and is what the forwarder includes;
#   - no header of the new layout has the old flat name (the forwarder would shadow nothing);
#   - CHANGELOG.md lists the old path, so a user who reads the warning finds the move there.
# Then one translation unit includes every forwarder: the compiler must accept it and print
# each forwarder's warning, as a user who builds old code will see it.
cmake_minimum_required(VERSION 3.21)
foreach(required CXX INCLUDES SOURCE WORK)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "forwarders_case.cmake: -D${required}=... is required")
  endif()
endforeach()

file(GLOB forwarders RELATIVE "${SOURCE}/compat/rt" "${SOURCE}/compat/rt/*.hpp")
list(LENGTH forwarders count)
if(count EQUAL 0)
  message(FATAL_ERROR "compat/rt holds no forwarder: expected one for each header that moved in 0.2.0")
endif()
file(READ "${SOURCE}/CHANGELOG.md" changelog)

set(problems "")
set(unit "")
set(expected_warnings "")
foreach(name IN LISTS forwarders)
  set(where "compat/rt/${name}")
  file(STRINGS "${SOURCE}/${where}" warning_lines REGEX "^#warning ")
  list(LENGTH warning_lines warnings)
  if(NOT warnings EQUAL 1)
    string(APPEND problems "${where}: expected one #warning line, found ${warnings}\n")
    continue()
  endif()
  if(NOT warning_lines MATCHES "^#warning \"(<rt/${name}> is deprecated: include ([^\"]*))\"$")
    string(APPEND problems "${where}: expected #warning \"<rt/${name}> is deprecated: include <rt/...>\", found ${warning_lines}\n")
    continue()
  endif()
  set(text "${CMAKE_MATCH_1}")
  string(REGEX MATCHALL "<rt/[a-z0-9_/]+[.]hpp>" named "${CMAKE_MATCH_2}")
  file(STRINGS "${SOURCE}/${where}" include_lines REGEX "^#include ")
  set(included "")
  foreach(line IN LISTS include_lines)
    string(REGEX REPLACE "^#include " "" line "${line}")
    list(APPEND included "${line}")
  endforeach()
  if(NOT named STREQUAL included)
    string(APPEND problems "${where}: its warning names ${named} but it includes ${included}; expected the same headers\n")
  endif()
  foreach(header IN LISTS named)
    string(REGEX REPLACE "^<(.*)>$" "\\1" path "${header}")
    if(NOT EXISTS "${SOURCE}/include/${path}")
      string(APPEND problems "${where}: names ${header}, which is not under include/; expected a header of the new layout\n")
    endif()
  endforeach()
  if(EXISTS "${SOURCE}/include/rt/${name}")
    string(APPEND problems "${where}: include/rt/${name} exists too; expected the old flat path to be the forwarder's alone\n")
  endif()
  string(FIND "${changelog}" "`<rt/${name}>`" listed)
  if(listed EQUAL -1)
    string(APPEND problems "${where}: CHANGELOG.md does not list `<rt/${name}>`; expected every moved path in its table\n")
  endif()
  string(APPEND unit "#include <rt/${name}>\n")
  list(APPEND expected_warnings "${text}")
endforeach()

if(problems)
  message(FATAL_ERROR "compat forwarders:\n${problems}")
endif()

file(MAKE_DIRECTORY "${WORK}")
file(WRITE "${WORK}/every_forwarder.cpp" "${unit}int main() { return 0; }\n")
string(REPLACE "|" ";" include_dirs "${INCLUDES}")
set(include_flags "")
foreach(dir IN LISTS include_dirs)
  if(dir AND NOT dir MATCHES "^/usr(/local)?/include/?$") # the compiler's own: -I there breaks #include_next
    list(APPEND include_flags "-I${dir}")
  endif()
endforeach()
separate_arguments(extra_flags UNIX_COMMAND "${FLAGS}")
execute_process(
  COMMAND "${CXX}" ${extra_flags} -std=c++17 -fsyntax-only ${include_flags} "${WORK}/every_forwarder.cpp"
  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "a file that includes every old path did not compile (exit ${result}); "
                      "expected each forwarder to bring its new header:\n${err}")
endif()
set(missing "")
foreach(text IN LISTS expected_warnings)
  string(FIND "${err}" "${text}" at)
  if(at EQUAL -1)
    string(APPEND missing "  ${text}\n")
  endif()
endforeach()
if(missing)
  message(FATAL_ERROR "the compiler did not print these deprecation warnings; expected each old path to warn:\n${missing}"
                      "compiler output:\n${err}")
endif()
message(STATUS "${count} old paths compile and warn with the new path")
