# Installs the build into a fresh prefix and renders the Cornell box sample with the installed
# tools only, from a working folder outside the build tree: what a user of
# `cmake --install build --prefix DIR` gets must work without the build tree's paths.
# Variables: BUILD_DIR, PREFIX, SAMPLE (an OBJ).
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}" --component kdray
                RESULT_VARIABLE status OUTPUT_QUIET)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${status}")
endif()

set(work "${PREFIX}/work")
file(MAKE_DIRECTORY "${work}")
function(run)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${work}" RESULT_VARIABLE status ERROR_VARIABLE err
                  OUTPUT_QUIET)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${ARGN}\nexited ${status}: ${err}")
  endif()
endfunction()

set(bin "${PREFIX}/bin")
foreach(tool kdconvert kdbuild kdrender kdtrace kdinfo kdcompare)
  run("${bin}/${tool}" --version)
endforeach()
run("${bin}/kdconvert" --quiet "${SAMPLE}" cornell.kdscene)
run("${bin}/kdbuild" --quiet cornell.kdscene cornell.kdtree)
run("${bin}/kdinfo" --quiet cornell.kdscene cornell.kdtree)
run("${bin}/kdrender" cornell.kdscene cornell.kdtree -o cornell.png --width 32 --height 32 --spp 4 --quiet)
if(NOT EXISTS "${work}/cornell.png")
  message(FATAL_ERROR "the installed kdrender wrote no image")
endif()
# A texture needs the codec module, which the installed tools find beside themselves.
file(WRITE "${work}/checker.ppm" "P3\n2 2\n255\n255 255 255 0 0 0\n0 0 0 255 255 255\n")
file(WRITE "${work}/textured.mtl" "newmtl checker\nKd 1 1 1\nmap_Kd checker.ppm\n")
file(WRITE "${work}/textured.obj" "mtllib textured.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                  "usemtl checker\nf 1/1 2/2 3/3\n")
execute_process(COMMAND "${bin}/kdconvert" --json textured.obj textured.kdscene WORKING_DIRECTORY "${work}"
                RESULT_VARIABLE status OUTPUT_VARIABLE report ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "kdconvert of a textured OBJ exited ${status}: ${err}")
endif()
string(JSON textures GET "${report}" textures)
if(NOT textures EQUAL 1)
  message(FATAL_ERROR "the installed kdconvert decoded no texture (is the codec module found?): ${report}")
endif()
file(REMOVE_RECURSE "${PREFIX}")
