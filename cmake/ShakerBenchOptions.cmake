# Warnings, sanitizers and the module helper as INTERFACE targets (style.md, pbrt-v4).

add_library(sb_warnings INTERFACE)
add_library(sb::warnings ALIAS sb_warnings)
target_compile_options(sb_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Wnon-virtual-dtor
  -Wold-style-cast -Woverloaded-virtual -Wdouble-promotion -Wformat=2
  $<$<BOOL:${SB_WARNINGS_AS_ERRORS}>:-Werror>)
# g++ 12 reports -Wrestrict inside libstdc++ for ordinary std::string concatenation at -O2
# (GCC bug 105329, fixed in 13); the warning says nothing about our code there.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(sb_warnings INTERFACE -Wno-restrict)
endif()

# The default build targets the baseline of the architecture, so that a result is the same on
# every machine. SB_NATIVE_ARCH uses this machine's instructions (AVX2, AVX-512) for speed;
# without SB_FUSED_MULTIPLY_ADD the compiler may not fuse a*b+c into one rounding
# (-ffp-contract=off), which keeps the DEM's arithmetic bitwise the default build's; with it
# every fused product rounds once instead of twice, so trajectories part in the last bits and,
# the beds being chaotic, a run is another filling's (docs/performance.md). Eigen's vectorised
# reductions over long vectors (the structure's modal products) take the wider registers'
# summation order in either case.
if(SB_NATIVE_ARCH)
  add_compile_options(-march=native)
  if(NOT SB_FUSED_MULTIPLY_ADD)
    add_compile_options(-ffp-contract=off)
  endif()
elseif(SB_FUSED_MULTIPLY_ADD)
  message(FATAL_ERROR "SB_FUSED_MULTIPLY_ADD needs SB_NATIVE_ARCH (the baseline has no FMA)")
endif()

add_library(sb_sanitizers INTERFACE)
add_library(sb::sanitizers ALIAS sb_sanitizers)
if(SB_SANITIZE OR SB_FUZZ)
  target_compile_options(sb_sanitizers INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(sb_sanitizers INTERFACE -fsanitize=address,undefined)
endif()
if(SB_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "SB_FUZZ needs clang (libFuzzer): use the 'fuzz' preset")
  endif()
  # Every library records the coverage libFuzzer steers by, except the sources of
  # fuzz/coverage-ignorelist.txt; only the targets in fuzz/ link libFuzzer's main
  # (-fsanitize=fuzzer there).
  target_compile_options(sb_sanitizers INTERFACE -fsanitize=fuzzer-no-link
    -fsanitize-coverage-ignorelist=${PROJECT_SOURCE_DIR}/fuzz/coverage-ignorelist.txt)
endif()

# sb_add_module(NAME SOURCES ... DEPENDS ...): a library target sb_NAME with alias sb::NAME,
# the repository root as include root (headers are included as "NAME/file.hpp").
function(sb_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS;PRIVATE_DEPENDS" ${ARGN})
  if(ARG_SOURCES)
    add_library(sb_${name} STATIC ${ARG_SOURCES})
    target_include_directories(sb_${name} PUBLIC ${PROJECT_SOURCE_DIR})
    target_link_libraries(sb_${name} PUBLIC ${ARG_DEPENDS} PRIVATE sb::warnings ${ARG_PRIVATE_DEPENDS})
    target_link_libraries(sb_${name} PUBLIC sb::sanitizers)
  else()
    add_library(sb_${name} INTERFACE)
    target_include_directories(sb_${name} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(sb_${name} INTERFACE ${ARG_DEPENDS} sb::sanitizers)
  endif()
  add_library(sb::${name} ALIAS sb_${name})
endfunction()

# sb_add_test(NAME LABEL [SERIAL] [BESIDE_OTHERS FILTER] SOURCES ... DEPENDS ...): one
# GoogleTest executable registered with CTest, every test in it carrying LABEL (unit,
# validation, slow or long: runs of minutes that the ci test preset leaves out). SERIAL:
# the tests run alone (RUN_SERIAL) with passive OpenMP waiting, for suites that run campaigns
# on several threads, so that ctest -j never puts two of them on the two cores and no idle
# thread spins at a barrier. BESIDE_OTHERS: the tests of a SERIAL suite that match the
# GoogleTest filter run on one thread and may share the machine; being long, they are started
# first (COST), so that the other core works through the rest meanwhile. ONE_PROCESS: the
# whole executable is one CTest test, so that its tests share what they build once (a DEM bed
# that takes most of each test's time under the sanitizers); started first, as it is long.
function(sb_add_test name label)
  cmake_parse_arguments(ARG "SERIAL;ONE_PROCESS" "BESIDE_OTHERS" "SOURCES;DEPENDS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} sb_test_main sb::warnings)
  target_compile_definitions(${name} PRIVATE SB_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  if(ARG_SERIAL AND ARG_BESIDE_OTHERS)
    gtest_discover_tests(${name} TEST_FILTER "${ARG_BESIDE_OTHERS}" TEST_LIST ${name}_beside
      PROPERTIES LABELS ${label} COST 1000 DISCOVERY_TIMEOUT 60)
    gtest_discover_tests(${name} TEST_FILTER "-${ARG_BESIDE_OTHERS}" TEST_LIST ${name}_alone
      PROPERTIES LABELS ${label} RUN_SERIAL TRUE ENVIRONMENT "OMP_WAIT_POLICY=PASSIVE"
      DISCOVERY_TIMEOUT 60)
  elseif(ARG_ONE_PROCESS)
    add_test(NAME ${name} COMMAND ${name})
    set_tests_properties(${name} PROPERTIES LABELS ${label} COST 1000)
  elseif(ARG_SERIAL)
    gtest_discover_tests(${name} PROPERTIES LABELS ${label} RUN_SERIAL TRUE
      ENVIRONMENT "OMP_WAIT_POLICY=PASSIVE" DISCOVERY_TIMEOUT 60)
  else()
    gtest_discover_tests(${name} PROPERTIES LABELS ${label} DISCOVERY_TIMEOUT 60)
  endif()
  # The sanitizer job builds only the unit suites (target sb_unit_tests, tests/CMakeLists.txt).
  set_property(GLOBAL APPEND PROPERTY SB_TESTS_${label} ${name})
endfunction()
