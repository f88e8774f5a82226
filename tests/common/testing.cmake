# Test helpers shared by every tests/<module>/CMakeLists.txt (included before them).

# vmass_expect_exit(NAME EXIT_CODE REGEX COMMAND...): runs COMMAND and passes when it exits with
# EXIT_CODE and, unless REGEX is "", its standard output or error matches the extended regular
# expression REGEX. So a check of a failure checks the failure it expects, not any failure.
function(vmass_expect_exit name exit_code regex)
  add_test(NAME ${name}
    COMMAND sh ${PROJECT_SOURCE_DIR}/tests/common/expect_exit.sh ${exit_code} "${regex}" ${ARGN})
endfunction()

# The shared test helpers' headers (tests/common): link it to use them.
add_library(vmass_test_common INTERFACE)
target_include_directories(vmass_test_common INTERFACE ${CMAKE_CURRENT_LIST_DIR})

# The counting operator new (allocation_counter.hpp): link it into a test executable that checks
# a hot path allocates nothing (one per executable: it replaces the global operator new).
add_library(vmass_test_allocation_counter OBJECT
  ${CMAKE_CURRENT_LIST_DIR}/allocation_counter.cpp)
target_link_libraries(vmass_test_allocation_counter PUBLIC vmass_test_common PRIVATE vmass_warnings)
