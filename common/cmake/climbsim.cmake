# Helpers shared by every CMakeLists of climbsim.

include(GoogleTest)
include(${CMAKE_CURRENT_LIST_DIR}/service_links.cmake)

# Where the services find deploy/qos/climbsim.xml when neither --qos nor
# CLIMBSIM_QOS_FILE says otherwise.
set(CLIMBSIM_DEFAULT_QOS_FILE "${PROJECT_SOURCE_DIR}/deploy/qos/climbsim.xml")

# climbsim_python_unittests(PREFIX <ctest prefix> MODULE <test module> LABELS <...>
#   [ENV <VAR=value ...>] [PROPERTIES <other ctest properties...>] TESTS <Class.test_name ...>)
# One ctest per Python unittest method, run by <build>/bin/climbsim-python in the calling folder;
# named <prefix>.<Class>.<name without test_>.
function(climbsim_python_unittests)
  cmake_parse_arguments(ARG "" "PREFIX;MODULE" "LABELS;ENV;PROPERTIES;TESTS" ${ARGN})
  foreach(test ${ARG_TESTS})
    string(REGEX REPLACE "\\.test_" "." short ${test})
    add_test(NAME ${ARG_PREFIX}.${short}
      COMMAND ${CMAKE_RUNTIME_OUTPUT_DIRECTORY}/climbsim-python -m unittest -v ${ARG_MODULE}.${test}
      WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
    set_tests_properties(${ARG_PREFIX}.${short} PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT 600
      ENVIRONMENT "${ARG_ENV}" ${ARG_PROPERTIES})
  endforeach()
endfunction()

# climbsim_service(NAME <exe> SOURCES <main.cpp ...> LIBS <libs...>)
# One executable per service, linked with the participant runtime.
function(climbsim_service)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE climbsim_common ${ARG_LIBS})
endfunction()

# climbsim_gtest(NAME <test> SOURCES <...> LIBS <...> [LABELS <...>])
# One GoogleTest executable, registered with ctest test by test.
function(climbsim_gtest)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  gtest_discover_tests(${ARG_NAME} PROPERTIES LABELS "${ARG_LABELS}" DISCOVERY_TIMEOUT 30)
endfunction()

# climbsim_configure(<service> LIBS <libs...>)
# The service's one configuration path, services/<service>/configure.cpp, as the library
# climbsim_<service>_configure (no DDS): (scenario, robot, options) -> its model's parameters,
# for the service's main and climbsim solo, included as "<service>/configure.hpp".
function(climbsim_configure SERVICE)
  cmake_parse_arguments(ARG "" "" "LIBS" ${ARGN})
  add_library(climbsim_${SERVICE}_configure STATIC configure.cpp)
  target_include_directories(climbsim_${SERVICE}_configure PUBLIC ${PROJECT_SOURCE_DIR}/services)
  target_link_libraries(climbsim_${SERVICE}_configure PUBLIC ${ARG_LIBS})
endfunction()

# climbsim_add_subdirectories(): add_subdirectory() for every folder next to the calling
# CMakeLists.txt that has a CMakeLists.txt of its own, in name order. A new folder (a service, a
# test area) is picked up at the next build: adding one touches no list.
function(climbsim_add_subdirectories)
  file(GLOB lists CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*/CMakeLists.txt)
  list(SORT lists)
  foreach(list IN LISTS lists)
    get_filename_component(dir ${list} DIRECTORY)
    add_subdirectory(${dir})
  endforeach()
endfunction()
