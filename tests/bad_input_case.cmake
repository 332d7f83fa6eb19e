# bad_input_case.cmake - runs one case of the bad-input catalogue
# (tests/bad_inputs/README.md) and checks what the README promises: exit code 1,
# empty stdout, one line on stderr starting with the case's location and
# containing its words, and every file of the folder untouched.
#
#   cmake -DPROGRAM=<stage02_generate_rays> -DCATALOGUE=<tests/bad_inputs>
#         -DWORK=<scratch folder> -DCASE=<case> [-DEMULATOR=<wine>] -P bad_input_case.cmake
# EMULATOR runs a cross-built program (CMAKE_CROSSCOMPILING_EMULATOR: Wine, qemu).
cmake_minimum_required(VERSION 3.21)
include("${CMAKE_CURRENT_LIST_DIR}/skip.cmake") # rt_skip

foreach(variable IN ITEMS PROGRAM CATALOGUE WORK CASE)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "bad_input_case.cmake: -D${variable}=... is missing")
  endif()
endforeach()

# --- the case's row: | `case` | what | `arguments` | `fragment` `fragment`... |
file(READ "${CATALOGUE}/README.md" readme)
string(REPLACE ";" "," readme "${readme}") # rows hold no ';' (see the README)
string(REPLACE "\n" ";" lines "${readme}")
set(row "")
foreach(line IN LISTS lines)
  if(line MATCHES "^\\| `([^`]+)` \\|" AND CMAKE_MATCH_1 STREQUAL CASE)
    set(row "${line}")
  endif()
endforeach()
if(row STREQUAL "")
  message(FATAL_ERROR "no row for case '${CASE}' in ${CATALOGUE}/README.md")
endif()
string(REGEX MATCHALL "[^|]+" cells "${row}")
list(LENGTH cells cell_count)
if(NOT cell_count EQUAL 4)
  message(FATAL_ERROR "the row of '${CASE}' has ${cell_count} cells, not 4: ${row}")
endif()
list(GET cells 2 arguments_cell)
list(GET cells 3 message_cell)
string(REGEX MATCH "`([^`]*)`" ignored "${arguments_cell}")
separate_arguments(arguments UNIX_COMMAND "${CMAKE_MATCH_1}")
string(REGEX MATCHALL "`[^`]*`" fragments "${message_cell}")
list(TRANSFORM fragments REPLACE "`" "")
list(LENGTH fragments fragment_count)
if(fragment_count EQUAL 0)
  message(FATAL_ERROR "the row of '${CASE}' quotes no message fragment")
endif()

# --- a copy of the catalogue, with a previous image out.ppm -----------------
set(folder "${WORK}/in")
if(EXISTS "${WORK}/in/readonly")
  file(CHMOD "${WORK}/in/readonly" DIRECTORY_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${folder}")
file(COPY "${CATALOGUE}/" DESTINATION "${folder}")
set(previous_image "P6\n1 1\n255\nrt!")
file(WRITE "${folder}/out.ppm" "${previous_image}")

if("${arguments}" MATCHES "READONLY/")
  # A folder the program cannot write into. Root writes through permissions,
  # so then use /proc, where nobody can create files.
  file(MAKE_DIRECTORY "${folder}/readonly")
  file(WRITE "${folder}/readonly/out.ppm" "${previous_image}")
  file(CHMOD "${folder}/readonly" DIRECTORY_PERMISSIONS OWNER_READ OWNER_EXECUTE)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E touch "${folder}/readonly/probe" RESULT_VARIABLE touched
                  OUTPUT_QUIET ERROR_QUIET)
  if(touched EQUAL 0)
    file(CHMOD "${folder}/readonly" DIRECTORY_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
    file(REMOVE "${folder}/readonly/probe")
    execute_process(COMMAND "${CMAKE_COMMAND}" -E touch "/proc/rt-probe" RESULT_VARIABLE touched
                    OUTPUT_QUIET ERROR_QUIET)
    if(NOT IS_DIRECTORY "/proc" OR touched EQUAL 0)
      rt_skip("no folder here is unwritable for this user")
      return()
    endif()
    set(readonly "/proc/")
  else()
    set(readonly "readonly/")
  endif()
  list(TRANSFORM arguments REPLACE "^READONLY/" "${readonly}")
  list(TRANSFORM fragments REPLACE "^READONLY/" "${readonly}")
endif()

# The folder's state: a list of "path sha256" for its files and "path/" for its folders.
function(snapshot folder result)
  file(GLOB_RECURSE files LIST_DIRECTORIES true RELATIVE "${folder}" "${folder}/*")
  list(SORT files)
  set(state "")
  foreach(file IN LISTS files)
    if(IS_DIRECTORY "${folder}/${file}")
      list(APPEND state "${file}/")
    else()
      file(SHA256 "${folder}/${file}" hash)
      list(APPEND state "${file} ${hash}")
    endif()
  endforeach()
  set(${result} "${state}" PARENT_SCOPE)
endfunction()
snapshot("${folder}" before)

# --- run it ------------------------------------------------------------------
execute_process(COMMAND ${EMULATOR} "${PROGRAM}" ${arguments}
                WORKING_DIRECTORY "${folder}"
                RESULT_VARIABLE exit_code OUTPUT_VARIABLE out ERROR_VARIABLE err
                TIMEOUT 60)
snapshot("${folder}" after)
if(EXISTS "${folder}/readonly")
  file(CHMOD "${folder}/readonly" DIRECTORY_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
endif()

# --- check it ----------------------------------------------------------------
# In a student kit, an input the camera rules refuse reaches the stage-01
# exercise first: exit 3 names it, and the case cannot be judged yet.
if("${exit_code}" STREQUAL "3" AND err MATCHES "not done yet: stage")
  rt_skip("${err}")
  return()
endif()
get_filename_component(program_name "${PROGRAM}" NAME_WE)
set(problems "")
if(NOT "${exit_code}" STREQUAL "1")
  string(APPEND problems "\n- exit code: expected 1 (an rt::error), found '${exit_code}'")
endif()
if(NOT "${out}" STREQUAL "")
  string(APPEND problems "\n- stdout: expected nothing, found '${out}'")
endif()
string(REPLACE "\n" "" err_without_breaks "${err}")
string(LENGTH "${err}" err_length)
string(LENGTH "${err_without_breaks}" err_length_without_breaks)
math(EXPR line_breaks "${err_length} - ${err_length_without_breaks}")
if(NOT line_breaks EQUAL 1 OR NOT "${err}" MATCHES "\n$")
  string(APPEND problems "\n- stderr: expected exactly one line, found ${line_breaks} line break(s)")
endif()
set(prefix "${program_name}: ")
string(LENGTH "${prefix}" prefix_length)
set(first TRUE)
foreach(fragment IN LISTS fragments)
  string(FIND "${err}" "${fragment}" at)
  if(first AND NOT at EQUAL prefix_length)
    string(APPEND problems "\n- stderr: expected to start with '${prefix}${fragment}'")
  elseif(at EQUAL -1)
    string(APPEND problems "\n- stderr: expected to contain '${fragment}'")
  endif()
  set(first FALSE)
endforeach()
if(NOT "${before}" STREQUAL "${after}")
  set(changed "${before}")
  list(REMOVE_ITEM changed ${after})
  set(added "${after}")
  list(REMOVE_ITEM added ${before})
  list(JOIN changed ", " changed)
  list(JOIN added ", " added)
  string(APPEND problems "\n- files: expected the folder untouched, found changed or removed: [${changed}], "
                        "added or changed: [${added}]")
endif()

if(NOT problems STREQUAL "")
  message(FATAL_ERROR "bad input '${CASE}': ${program_name} ${arguments}${problems}\n"
                      "exit code: ${exit_code}\nstdout: ${out}\nstderr: ${err}")
endif()
message(STATUS "bad input '${CASE}': exit 1, one line, files untouched: ${err}")
