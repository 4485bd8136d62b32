# ctest driver for the sanitizer build: configures the project with AddressSanitizer and
# UndefinedBehaviorSanitizer in BUILD_DIR (<build>/sanitize; incremental after the first run),
# builds the test executables of a subset of the quick label and runs their quick tests there.
# Any ASan report (out-of-bounds, use-after-free, leak) or UBSan report (overflow, misaligned or
# null access, bad shift, invalid enum/bool) aborts the test binary and fails this test.
#   cmake -DSOURCE_DIR=<repo> -DBUILD_DIR=<build>/sanitize -DTARGETS="core_tests;..." -P run_sanitized.cmake
# The subset (TARGETS) is chosen to bound CI time: see docs/performance.md ("Sanitizer build").
foreach(v SOURCE_DIR BUILD_DIR TARGETS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_sanitized.cmake: -D${v}=... is required")
  endif()
endforeach()

set(flags "-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all")
if(NOT EXISTS ${BUILD_DIR}/CMakeCache.txt)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BUILD_DIR}
                          -DCMAKE_BUILD_TYPE=Sanitize
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

# Only the executables built above have tests discovered; run their quick ones.
string(REPLACE ";" "|" pattern "${TARGETS}")
set(ENV{ASAN_OPTIONS} "detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1")
set(ENV{UBSAN_OPTIONS} "print_stacktrace=1:halt_on_error=1")
set(ENV{LSAN_OPTIONS} "suppressions=${SOURCE_DIR}/tests/sanitize/lsan.supp:print_suppressions=0")
execute_process(COMMAND ${CMAKE_CTEST_COMMAND} --test-dir ${BUILD_DIR} -L quick -j 2 --output-on-failure
                        --timeout 900
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "a sanitized quick test failed (see the ASan/UBSan report above); build in ${BUILD_DIR}")
endif()
