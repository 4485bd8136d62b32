# ctest driver for the loader fuzzer: configure + build the clang sub-build (incremental after the
# first run), then fuzz for SECONDS seconds from the seed corpora. A crash, sanitizer report or an
# exception other than tyndall::Error fails the test and leaves the input in BUILD_DIR as crash-*.
#   cmake -DSOURCE_DIR=<repo> -DBUILD_DIR=<build>/fuzz -DCLANGXX=clang++ -DSECONDS=60 -P run_fuzz.cmake
foreach(v SOURCE_DIR BUILD_DIR CLANGXX SECONDS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_fuzz.cmake: -D${v}=... is required")
  endif()
endforeach()

if(NOT EXISTS ${BUILD_DIR}/CMakeCache.txt)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/fuzz -B ${BUILD_DIR} -DCMAKE_CXX_COMPILER=${CLANGXX}
                          -DCMAKE_BUILD_TYPE=None
                  RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "configuring the fuzz build failed")
  endif()
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} -j 2 RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the fuzz target failed")
endif()

# New inputs go to a corpus in the build tree; the seeds in the repository stay read-only.
file(MAKE_DIRECTORY ${BUILD_DIR}/corpus)
execute_process(COMMAND ${BUILD_DIR}/scene_loader_fuzz
                        -max_total_time=${SECONDS} -timeout=10 -rss_limit_mb=2048 -max_len=65536
                        -print_final_stats=1 -dict=${SOURCE_DIR}/fuzz/scene.dict
                        -artifact_prefix=${BUILD_DIR}/
                        ${BUILD_DIR}/corpus ${SOURCE_DIR}/fuzz/seeds ${SOURCE_DIR}/scenes
                WORKING_DIRECTORY ${BUILD_DIR}
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "the scene loader fuzzer found a failure (exit ${rc}); the input is in ${BUILD_DIR}/crash-*")
endif()
