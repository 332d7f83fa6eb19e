# non_ascii_paths.cmake - file names outside ASCII, on the command line and
# inside a scene and an OBJ file, open the same files on every system.
#
# A folder "dossier-é" holds "scène-ñ.scene", which names the mesh
# "modèle-ü.obj", whose material library is "matériau-ø.mtl". Each program
# renders it to an output named outside ASCII; then a missing input and an OBJ
# error must be named in the message as they were typed (UTF-8), never as
# "scÃ¨ne" (a name read byte by byte, as MinGW's std::filesystem::path does
# with a std::string) or "sc?ne".
#
#   cmake -DPROGRAMS=<stage02>|<stage08> -DWORK=<scratch folder> [-DEMULATOR=<wine>] -P non_ascii_paths.cmake
cmake_minimum_required(VERSION 3.21)
include("${CMAKE_CURRENT_LIST_DIR}/skip.cmake") # rt_skip

foreach(variable IN ITEMS PROGRAMS WORK)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "non_ascii_paths.cmake: -D${variable}=... is missing")
  endif()
endforeach()

string(REPLACE "|" ";" PROGRAMS "${PROGRAMS}")
set(folder "${WORK}/dossier-é")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${folder}")
file(WRITE "${folder}/scène-ñ.scene"
  "image 16 12\n"
  "camera perspective eye 0 1 4 look_at 0 0.5 0 up 0 1 0 fov 40\n"
  "material grey kd 0.6 0.6 0.6\n"
  "sphere center 0 0.5 0 radius 0.5 material grey\n"
  "mesh modèle-ü.obj material grey\n"
  "light point position 2 4 3 intensity 1 1 1\n")
file(WRITE "${folder}/modèle-ü.obj"
  "mtllib matériau-ø.mtl\nv -2 0 -2\nv 2 0 -2\nv 0 0 2\nusemtl sol\nf 1 3 2\n")
file(WRITE "${folder}/matériau-ø.mtl" "newmtl sol\nKd 0.8 0.7 0.6\n")
file(WRITE "${folder}/cassé-ø.scene"
  "image 16 12\n"
  "camera perspective eye 0 1 4 look_at 0 0.5 0 up 0 1 0 fov 40\n"
  "material grey kd 0.6 0.6 0.6\n"
  "mesh cassé-ø.obj material grey\n")
file(WRITE "${folder}/cassé-ø.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
file(SHA256 "${folder}/scène-ñ.scene" scene_before)

# Runs `program` on `scene` in `folder`: exit code 1 and a message naming
# `named`, or a line in `problems`.
function(expect_refusal program scene named)
  get_filename_component(name "${program}" NAME_WE)
  execute_process(COMMAND ${EMULATOR} "${program}" "${scene}" -o "x.ppm"
                  WORKING_DIRECTORY "${folder}" RESULT_VARIABLE code ERROR_VARIABLE err OUTPUT_QUIET TIMEOUT 120)
  string(FIND "${err}" "${named}" at)
  if(NOT "${code}" STREQUAL "1" OR at EQUAL -1)
    string(APPEND problems "\n- ${name} ${scene}: expected exit code 1 and a message naming '${named}', "
                           "found exit code '${code}' and: ${err}")
    set(problems "${problems}" PARENT_SCOPE)
  endif()
endfunction()

set(problems "")
foreach(program IN LISTS PROGRAMS)
  get_filename_component(name "${program}" NAME_WE)
  # a scene and an output named outside ASCII
  execute_process(COMMAND ${EMULATOR} "${program}" "scène-ñ.scene" -o "sortie-ü-${name}.ppm"
                  WORKING_DIRECTORY "${folder}" RESULT_VARIABLE code ERROR_VARIABLE err OUTPUT_QUIET TIMEOUT 120)
  if("${code}" STREQUAL "3" AND err MATCHES "not done yet: stage")
    rt_skip("${err}") # a student kit: an exercise on the way is not finished
    return()
  endif()
  if(NOT "${code}" STREQUAL "0")
    string(APPEND problems "\n- ${name} scène-ñ.scene -o sortie-ü-${name}.ppm: expected exit code 0, found '${code}': ${err}")
  elseif(NOT EXISTS "${folder}/sortie-ü-${name}.ppm")
    string(APPEND problems "\n- ${name}: expected the image 'sortie-ü-${name}.ppm', found none: ${err}")
  else()
    file(READ "${folder}/sortie-ü-${name}.ppm" head LIMIT 3)
    if(NOT head MATCHES "^P[36]\n")
      string(APPEND problems "\n- ${name}: expected a PPM in 'sortie-ü-${name}.ppm', found one starting '${head}'")
    endif()
  endif()

  # a missing input is named as typed; an error inside an OBJ file that a
  # scene names, at its location as written
  expect_refusal("${program}" "absent-é.scene" "absent-é.scene")
  expect_refusal("${program}" "cassé-ø.scene" "cassé-ø.obj:4:")
endforeach()

file(SHA256 "${folder}/scène-ñ.scene" scene_after)
if(NOT scene_after STREQUAL scene_before)
  string(APPEND problems "\n- scène-ñ.scene: expected the input unchanged, found it changed")
endif()
if(NOT problems STREQUAL "")
  message(FATAL_ERROR "file names outside ASCII:${problems}")
endif()
