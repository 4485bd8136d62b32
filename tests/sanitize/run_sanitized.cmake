# ctest driver for the sanitizer build: configures the project with AddressSanitizer and
# UndefinedBehaviorSanitizer in BUILD_DIR (<build>/sanitize; incremental after the first run),
# builds the test executables TARGETS (suites whose tests are all in the quick label) and runs
# each once, all its tests in one process (ASan's start-up per test process would double the
# cost: docs/performance.md, "Sanitizer build").
# Any ASan report (out-of-bounds, use-after-free, leak) or UBSan report (overflow, misaligned or
# null access, bad shift, invalid enum/bool) aborts the test binary and fails this test.
#   cmake -DSOURCE_DIR=<repo> -DBUILD_DIR=<build>/sanitize -DTARGETS="core_tests;..." -P run_sanitized.cmake
foreach(v SOURCE_DIR BUILD_DIR TARGETS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_sanitized.cmake: -D${v}=... is required")
  endif()
endforeach()

# -Og and line tables only (-g1): file:line in every report. -Og compiles in about half the CPU time
# of -O1 under ASan + UBSan, and optimises less, so no more of what the sanitizers check is removed.
# Unity batches of 8 sources: each batch parses the heavy headers (OpenVDB, Embree, nlohmann/json,
# GoogleTest) and instantiates their templates once instead of once per file, a third less compiling
# (docs/performance.md, "CI and build time"). Names at file scope in a .cpp (anonymous namespace,
# static) must therefore be unique within its library or test executable.
set(flags "-Og -g1 -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all")
set(unity "")
if(EXISTS ${BUILD_DIR}/CMakeCache.txt)
  file(STRINGS ${BUILD_DIR}/CMakeCache.txt unity REGEX "^CMAKE_UNITY_BUILD:BOOL=ON$")
endif()
if(NOT unity)  # a new build directory, or one configured before the unity batches
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BUILD_DIR}
                          -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_UNITY_BUILD:BOOL=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8
                          "-DCMAKE_CXX_FLAGS_SANITIZE=${flags}"
                          "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined"
                          -DTYNDALL_BUILD_BENCH=OFF -DTYNDALL_BUILD_FUZZ=OFF -DTYNDALL_BUILD_SANITIZE=OFF
                  RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "configuring the sanitizer build failed")
  endif()
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} -j 2 --target ${TARGETS} RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the sanitized tests failed")
endif()

# new_delete_type_mismatch=0: OpenImageIO 2.4's own TextureSystem::destroy frees its
# TextureSystemImpl with a sized delete of the wrong size (the report's frames are all inside
# libOpenImageIO; every test that loads a texture hits it). Our code's deletes through a base
# without a virtual destructor are caught at compile time instead (-Wall: -Wdelete-non-virtual-dtor).
set(ENV{ASAN_OPTIONS} "detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:new_delete_type_mismatch=0")
set(ENV{UBSAN_OPTIONS} "print_stacktrace=1:halt_on_error=1")
set(ENV{LSAN_OPTIONS} "suppressions=${SOURCE_DIR}/tests/sanitize/lsan.supp:print_suppressions=0")
set(failed "")
foreach(t ${TARGETS})
  message(STATUS "sanitized: ${t}")
  execute_process(COMMAND ${BUILD_DIR}/tests/${t} --gtest_brief=1 WORKING_DIRECTORY ${BUILD_DIR}/tests
                  RESULT_VARIABLE rc TIMEOUT 900)
  if(rc)
    list(APPEND failed "${t} (${rc})")
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "sanitized tests failed: ${failed} (see the ASan/UBSan report above); build in ${BUILD_DIR}")
endif()
message(STATUS "sanitized tests clean: ${TARGETS}")
