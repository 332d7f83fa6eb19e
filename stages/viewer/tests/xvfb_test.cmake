# xvfb_test.cmake - ctest viewer.xvfb: the viewer in a virtual X server (xvfb-run),
# driven by a script, shows and saves exactly what stage08_output writes.
#
#   cmake -DVIEWER=... -DSTAGE08=... -DXVFB_RUN=... -DSCENE=... -DWORK=... -P xvfb_test.cmake
#
# 1. The viewer opens SCENE (96 x 64 pixels), waits for two levels, orbits, pans,
#    zooms, switches to the normals view and back, doubles the samples per pixel,
#    changes the filter, the max depth and the exposure, waits for the last level,
#    reads its window back (screenshot) and its title, saves the image and
#    writes the stage08_output arguments of that image.
# 2. stage08_output renders those arguments to .ppm and .png.
# 3. The screenshot equals stage08_output's .ppm byte for byte, and the saved PNG
#    its .png; the image differs from the scene's own camera (the input did
#    something); the title shows the view, 4/4 spp done, the time and the rays per second.
# 4. The depth view equals stage08_output --aov depth. 5. The ray inspector's story of a
#    clicked pixel equals stage08_output --pixel-json's, and its rays are drawn.
# Every step has a timeout: the viewer's own --timeout, coreutils' timeout around
# it, then execute_process's.
foreach(name VIEWER STAGE08 XVFB_RUN SCENE WORK)
  if(NOT DEFINED ${name})
    message(FATAL_ERROR "xvfb_test.cmake: expected -D${name}=..., found none")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

# the viewer stops itself after --timeout; coreutils' timeout also stops a viewer
# that hangs (xvfb-run's own end would leave it behind)
find_program(timeout_program timeout)
set(guard "")
if(timeout_program)
  set(guard "${timeout_program}" -k 10 150)
endif()

set(size --width 96 --height 64)
set(script "wait 2; orbit 60 -20; pan 12 -6; zoom 3; key 2; key 1; key ]; key f; key .; key =; wait; \
screenshot shot.ppm; title title.txt; save saved.png; args args.txt; quit")
execute_process(
  COMMAND "${XVFB_RUN}" -a -s "-screen 0 640x480x24"
          ${guard} "${VIEWER}" "${SCENE}" ${size} --spp 2 --threads 2 --timeout 120 --script "${script}"
  WORKING_DIRECTORY "${WORK}"
  RESULT_VARIABLE code
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err
  TIMEOUT 180)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "expected the scripted viewer to exit with 0, found '${code}':\n${out}${err}")
endif()
foreach(file shot.ppm title.txt saved.png args.txt)
  if(NOT EXISTS "${WORK}/${file}")
    message(FATAL_ERROR "expected the viewer to write ${file}, found none:\n${out}${err}")
  endif()
endforeach()

# the title: the view, the samples per pixel (4 of 4: --spp 2 doubled), done, the time, rays per second
file(READ "${WORK}/title.txt" title)
string(STRIP "${title}" title)
if(NOT title MATCHES "^rt viewer - shaded - 4/4 spp done - [0-9.]+ (s|min [0-9]+ s) - [0-9.]+ ?[kMG]?rays/s$")
  message(FATAL_ERROR "expected the title 'rt viewer - shaded - 4/4 spp done - TIME - RATE rays/s', found '${title}'")
endif()
message(STATUS "title: ${title}")

file(STRINGS "${WORK}/args.txt" arguments)
list(FIND arguments "--camera" camera_at)
if(camera_at LESS 0)
  message(FATAL_ERROR "expected --camera in the viewer's stage08_output arguments, found: ${arguments}")
endif()
message(STATUS "stage08_output ${arguments}")

function(render output)
  execute_process(
    COMMAND "${STAGE08}" ${ARGN} -o "${output}" --quiet
    WORKING_DIRECTORY "${WORK}"
    RESULT_VARIABLE code
    ERROR_VARIABLE err
    TIMEOUT 120)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "expected stage08_output to write ${output}, found exit '${code}': ${err}")
  endif()
endfunction()

render(reference.ppm ${arguments})
render(reference.png ${arguments})

# byte for byte; on a mismatch, how many bytes differ and by how much
function(expect_same actual expected what)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK}/${actual}" "${WORK}/${expected}"
                  RESULT_VARIABLE differ)
  if(differ EQUAL 0)
    message(STATUS "${what}: ${actual} equals ${expected}")
    return()
  endif()
  file(READ "${WORK}/${actual}" a HEX)
  file(READ "${WORK}/${expected}" b HEX)
  string(LENGTH "${a}" length_a)
  string(LENGTH "${b}" length_b)
  set(count 0)
  set(largest 0)
  if(length_a EQUAL length_b AND actual MATCHES "[.]ppm$")
    math(EXPR last "${length_a} / 2 - 1")
    foreach(k RANGE 0 ${last})
      math(EXPR at "2 * ${k}")
      string(SUBSTRING "${a}" ${at} 2 x)
      string(SUBSTRING "${b}" ${at} 2 y)
      if(NOT x STREQUAL y)
        math(EXPR count "${count} + 1")
        math(EXPR d "0x${x} - 0x${y}")
        if(d LESS 0)
          math(EXPR d "-${d}")
        endif()
        if(d GREATER largest)
          set(largest ${d})
        endif()
      endif()
    endforeach()
    math(EXPR bytes "${length_a} / 2")
    message(FATAL_ERROR "${what}: expected ${actual} to equal ${expected} byte for byte, found ${count} of ${bytes} "
                        "bytes that differ (by at most ${largest}); the window does not show the renderer's image")
  endif()
  message(FATAL_ERROR "${what}: expected ${actual} to equal ${expected}, found files of ${length_a} and "
                      "${length_b} hex digits that differ")
endfunction()

expect_same(shot.ppm reference.ppm "the window, read back")
expect_same(saved.png reference.png "the save")

# the scripted input moved the camera: the scene's own camera gives another image
list(REMOVE_AT arguments ${camera_at})
list(REMOVE_AT arguments ${camera_at})
render(unmoved.ppm ${arguments})
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK}/shot.ppm" "${WORK}/unmoved.ppm"
                RESULT_VARIABLE differ)
if(differ EQUAL 0)
  message(FATAL_ERROR "expected the orbit, pan and zoom to change the image, found the scene camera's image")
endif()

# 4. The depth view: a second run switches to it (key 3) and shows, byte for byte,
#    the PNG stage08_output stores for --aov depth (scaled by the farthest hit).
set(script "key 3; wait; screenshot depth-shot.ppm; args depth-args.txt; quit")
execute_process(
  COMMAND "${XVFB_RUN}" -a -s "-screen 0 640x480x24"
          ${guard} "${VIEWER}" "${SCENE}" ${size} --spp 1 --threads 2 --timeout 120 --script "${script}"
  WORKING_DIRECTORY "${WORK}"
  RESULT_VARIABLE code
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err
  TIMEOUT 180)
if(NOT code EQUAL 0 OR NOT EXISTS "${WORK}/depth-shot.ppm" OR NOT EXISTS "${WORK}/depth-args.txt")
  message(FATAL_ERROR "expected the scripted depth view to exit with 0 and write depth-shot.ppm and "
                      "depth-args.txt, found '${code}':\n${out}${err}")
endif()
file(STRINGS "${WORK}/depth-args.txt" arguments)
list(FIND arguments "depth" depth_at)
if(depth_at LESS 0)
  message(FATAL_ERROR "expected '--aov depth' in the viewer's stage08_output arguments, found: ${arguments}")
endif()
render(depth-reference.ppm ${arguments})
expect_same(depth-shot.ppm depth-reference.ppm "the depth view, read back")
file(READ "${WORK}/depth-shot.ppm" depth_bytes HEX)
if(NOT depth_bytes MATCHES "ffffff")
  message(FATAL_ERROR "expected the depth view's farthest hit to be white (ff ff ff), found no white pixel")
endif()

# 5. The ray inspector: a third run orbits, waits, turns the inspector on (key i),
#    clicks a pixel and writes that pixel's story as JSON: it must be, byte for
#    byte, what stage08_output --pixel-json prints for the same view and pixel;
#    the window shows the rays over the image, so it differs from the image.
set(script "orbit 30 -10; wait; key i; click 40 30; args inspect-args.txt; story story.json; \
screenshot inspect-shot.ppm; quit")
execute_process(
  COMMAND "${XVFB_RUN}" -a -s "-screen 0 640x480x24"
          ${guard} "${VIEWER}" "${SCENE}" ${size} --spp 1 --threads 2 --timeout 120 --script "${script}"
  WORKING_DIRECTORY "${WORK}"
  RESULT_VARIABLE code
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err
  TIMEOUT 180)
foreach(file inspect-args.txt story.json inspect-shot.ppm)
  if(NOT code EQUAL 0 OR NOT EXISTS "${WORK}/${file}")
    message(FATAL_ERROR "expected the scripted inspector to exit with 0 and write ${file}, found '${code}':\n"
                        "${out}${err}")
  endif()
endforeach()
if(NOT err MATCHES "ray inspector on" OR NOT err MATCHES "\\[0\\] camera: closest hit")
  message(FATAL_ERROR "expected the inspector to say it is on and print the pixel's story on stderr, found:\n${err}")
endif()
file(STRINGS "${WORK}/inspect-args.txt" arguments)
execute_process(
  COMMAND "${STAGE08}" ${arguments} --pixel-json 40 30
  WORKING_DIRECTORY "${WORK}"
  RESULT_VARIABLE code
  OUTPUT_FILE "${WORK}/story-reference.json"
  ERROR_VARIABLE err
  TIMEOUT 120)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "expected stage08_output --pixel-json 40 30 to exit with 0, found '${code}': ${err}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK}/story.json" "${WORK}/story-reference.json"
                RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  file(READ "${WORK}/story.json" mine)
  file(READ "${WORK}/story-reference.json" theirs)
  message(FATAL_ERROR "expected the inspector's story of pixel 40 30 to equal stage08_output --pixel-json's, found\n"
                      "${mine}\nagainst\n${theirs}")
endif()
message(STATUS "the inspector's story equals stage08_output --pixel-json 40 30")
render(inspect-reference.ppm ${arguments})
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK}/inspect-shot.ppm" "${WORK}/inspect-reference.ppm"
                RESULT_VARIABLE differ)
if(differ EQUAL 0)
  message(FATAL_ERROR "expected the inspector's rays drawn over the image, found the image alone")
endif()
