# Small helpers shared by every module's CMakeLists.

# Sets OUT to TRUE when MODULE is part of this build (LC2WF_ONLY empty = all modules).
function(lc2wf_module_enabled module out)
  if(LC2WF_ONLY STREQUAL "" OR module IN_LIST LC2WF_ONLY)
    set(${out} TRUE PARENT_SCOPE)
  else()
    set(${out} FALSE PARENT_SCOPE)
  endif()
endfunction()

# lc2wf_add_command(NAME SOURCES... LIBS libs...)
# A command-line program. Every one is listed in the global property LC2WF_COMMANDS, which the contract test
# (tests/repo/cli_contract_test.cpp) runs, so no command escapes the conventions of README.md.
function(lc2wf_add_command name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
  set_property(GLOBAL APPEND PROPERTY LC2WF_COMMANDS ${name})
endfunction()

# lc2wf_add_test(NAME SOURCES... LIBS libs...)
# One GoogleTest executable per test file group (with gmock's matchers), registered test-by-test with CTest.
function(lc2wf_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gmock GTest::gtest GTest::gtest_main)
  target_include_directories(${name} PRIVATE "${PROJECT_SOURCE_DIR}")  # tests/common/ helpers
  target_compile_definitions(${name} PRIVATE
    LC2WF_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    LC2WF_SHARED_DATA_DIR="${PROJECT_SOURCE_DIR}/../shared/data")
  include(GoogleTest)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60)
endfunction()
