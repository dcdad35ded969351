# Small helpers shared by every module's CMakeLists.

# Sets OUT to TRUE when MODULE is part of this build (LC2WF_ONLY empty = all modules).
function(lc2wf_module_enabled module out)
  if(LC2WF_ONLY STREQUAL "" OR module IN_LIST LC2WF_ONLY)
    set(${out} TRUE PARENT_SCOPE)
  else()
    set(${out} FALSE PARENT_SCOPE)
  endif()
endfunction()

# lc2wf_add_test(NAME SOURCES... LIBS libs... [LABELS labels...])
# One GoogleTest executable per test file group, registered test-by-test with CTest.
function(lc2wf_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  target_include_directories(${name} PRIVATE "${PROJECT_SOURCE_DIR}")  # tests/common/ helpers
  target_compile_definitions(${name} PRIVATE
    LC2WF_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    LC2WF_SHARED_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/data")
  include(GoogleTest)
  if(ARG_LABELS)
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${ARG_LABELS}")
  else()
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60)
  endif()
endfunction()
