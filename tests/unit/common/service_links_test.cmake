# The check of common/cmake/service_links.cmake on a tiny project (service_links_project/):
# the project as it is configures, and each bad link stops its configuration with the line
# that names the target and the other service's library.
#
# cmake -DCLIMBSIM_ROOT=<repository> -DWORK_DIR=<scratch folder> -DGENERATOR=<generator>
#       -P service_links_test.cmake

set(project_dir ${CMAKE_CURRENT_LIST_DIR}/service_links_project)
set(failures "")

# configure(<case> <rc_var> <output_var>)
function(configure case rc_var output_var)
  file(REMOVE_RECURSE ${WORK_DIR}/${case})
  execute_process(
    COMMAND ${CMAKE_COMMAND} -S ${project_dir} -B ${WORK_DIR}/${case} -G ${GENERATOR}
      -DCLIMBSIM_ROOT=${CLIMBSIM_ROOT} -DCLIMBSIM_CASE=${case}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(${rc_var} ${rc} PARENT_SCOPE)
  set(${output_var} "${out}${err}" PARENT_SCOPE)
endfunction()

# expect_refused(<case> <regex of the line naming the link>...)
function(expect_refused case)
  configure(${case} rc output)
  string(REGEX REPLACE "\n +" " " output "${output}")  # CMake wraps long message lines
  if(rc EQUAL 0)
    set(failures "${failures}\n${case}: configured, but must be refused" PARENT_SCOPE)
    return()
  endif()
  foreach(line IN LISTS ARGN)
    if(NOT output MATCHES "${line}")
      set(failures "${failures}\n${case}: refused without naming '${line}':\n${output}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  message(STATUS "${case}: refused, naming the link")
endfunction()

# The composer solo links both services, each service links common only: accepted.
configure(good rc output)
if(NOT rc EQUAL 0 OR NOT output MATCHES "no service links another")
  set(failures "${failures}\ngood: must configure and say 'no service links another':\n${output}")
else()
  message(STATUS "good: accepted")
endif()

expect_refused(node_links_another_model
  "a_node \\(services/a, owner a\\) links b_model of b"
  "a-service \\(services/a, owner a\\) links a_node -> b_model of b")
expect_refused(private_link
  "a_model \\(services/a, owner a\\) links b_node of b")
expect_refused(common_links_a_service
  "shared_thing \\(common, owner common\\) links b_model of b"
  "a_model \\(services/a, owner a\\) links shared_thing -> b_model of b")
expect_refused(compiles_another_services_file
  "a-service \\(services/a, owner a\\) compiles services/b/b_model.cpp of b")
expect_refused(includes_another_services_folder
  "a_node \\(services/a, owner a\\) includes services/b of b")

if(failures)
  message(FATAL_ERROR "service_links check:${failures}")
endif()
