# ctest driver for the fuzzers: configure + build the clang sub-build (incremental after the first
# run), then fuzz FUZZ_TARGET (default scene_loader_fuzz) for SECONDS seconds from its seed corpora. A
# crash, sanitizer report or an exception other than tyndall::Error fails the test and leaves the
# input in BUILD_DIR as <target>-crash-*.
#   cmake -DSOURCE_DIR=<repo> -DBUILD_DIR=<build>/fuzz -DCLANGXX=clang++ -DSECONDS=60 [-DFUZZ_TARGET=vdb_fuzz] -P run_fuzz.cmake
foreach(v SOURCE_DIR BUILD_DIR CLANGXX SECONDS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_fuzz.cmake: -D${v}=... is required")
  endif()
endforeach()
if(NOT DEFINED FUZZ_TARGET)
  set(FUZZ_TARGET scene_loader_fuzz)
endif()

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
  message(FATAL_ERROR "building the fuzz targets failed")
endif()

# Each target's seeds and options. New inputs go to a corpus in the build tree; the seeds in the
# repository stay read-only.
set(options -max_len=65536)
if(FUZZ_TARGET STREQUAL "scene_loader_fuzz")
  set(seeds ${SOURCE_DIR}/fuzz/seeds ${SOURCE_DIR}/scenes)
  list(APPEND options -dict=${SOURCE_DIR}/fuzz/scene.dict)
  set(corpus ${BUILD_DIR}/corpus)  # the name it always had
elseif(FUZZ_TARGET STREQUAL "checkpoint_fuzz")
  set(seeds ${SOURCE_DIR}/fuzz/seeds-checkpoint)
elseif(FUZZ_TARGET STREQUAL "view_file_fuzz")
  set(seeds ${SOURCE_DIR}/fuzz/seeds-view)
  list(APPEND options -dict=${SOURCE_DIR}/fuzz/scene.dict)
elseif(FUZZ_TARGET STREQUAL "vdb_fuzz")
  set(seeds ${BUILD_DIR}/vdb-seeds)
  file(MAKE_DIRECTORY ${seeds})
  execute_process(COMMAND ${BUILD_DIR}/make_vdb_seeds ${seeds} RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "writing the VDB seeds failed")
  endif()
  # OpenVDB leaks the node it is building when a read throws (RootNode::readTopology; not ours to
  # fix). Every size a damaged block records is checked before OpenVDB allocates it
  # (loading/vdb_stream.h); -malloc_limit_mb reports any allocation above -rss_limit_mb.
  list(APPEND options -detect_leaks=0)
  set(ENV{ASAN_OPTIONS} "detect_leaks=0")
else()
  message(FATAL_ERROR "run_fuzz.cmake: unknown FUZZ_TARGET ${FUZZ_TARGET}")
endif()
if(NOT DEFINED corpus)
  set(corpus ${BUILD_DIR}/corpus-${FUZZ_TARGET})
endif()
file(MAKE_DIRECTORY ${corpus})
execute_process(COMMAND ${BUILD_DIR}/${FUZZ_TARGET}
                        -max_total_time=${SECONDS} -timeout=10 -rss_limit_mb=2048 ${options}
                        -print_final_stats=1 -artifact_prefix=${BUILD_DIR}/${FUZZ_TARGET}-
                        ${corpus} ${seeds}
                WORKING_DIRECTORY ${BUILD_DIR}
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "${FUZZ_TARGET} found a failure (exit ${rc}); the input is in ${BUILD_DIR}/${FUZZ_TARGET}-crash-*")
endif()
