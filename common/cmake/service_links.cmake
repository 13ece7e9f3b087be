# Services side by side (docs/design.md#layout): the check that no service links another.
#
# Every target has an owner, the place it is defined in:
#   services/<name>/...  -> <name>      (a service, or the composer solo)
#   common/..., idl/...  -> common
#   deploy/launcher/...  -> launcher    (a composer)
#   tests/...            -> tests       (not checked: a test may link what it tests)
# The target property CLIMBSIM_OWNER, when set, overrides the place.
#
# The rules, checked by climbsim_check_service_links() over every target of the build:
#   - a service's target links (directly or through any library it links) only targets of its
#     own service, of common, and outside packages (imported targets, system libraries);
#   - a common target links only common targets and outside packages;
#   - no checked target compiles a source file of, or adds an include directory in, another
#     service's folder;
#   - the composers (CLIMBSIM_COMPOSERS: solo, launcher) may link every service's libraries.
# A broken rule stops the configuration with one line per offending link, naming the target,
# its owner, the library and the library's owner.

set(CLIMBSIM_COMPOSERS solo launcher)

# <out_var> = the owner of `target` (see above); "" for imported targets and targets defined
# outside services/, common/, idl/, deploy/launcher and tests/ (outside packages).
function(climbsim_owner_of target out_var)
  get_target_property(aliased ${target} ALIASED_TARGET)
  if(aliased)
    set(target ${aliased})
  endif()
  get_target_property(owner ${target} CLIMBSIM_OWNER)
  if(owner)
    set(${out_var} ${owner} PARENT_SCOPE)
    return()
  endif()
  get_target_property(imported ${target} IMPORTED)
  if(imported)
    set(${out_var} "" PARENT_SCOPE)
    return()
  endif()
  get_target_property(dir ${target} SOURCE_DIR)
  _climbsim_owner_of_path("${dir}" owner)
  set(${out_var} "${owner}" PARENT_SCOPE)
endfunction()

# <out_var> = the owner of the files under `path` (absolute); "" outside the project's folders.
function(_climbsim_owner_of_path path out_var)
  set(owner "")
  file(RELATIVE_PATH rel "${PROJECT_SOURCE_DIR}" "${path}")
  if(rel MATCHES "^services/([^/]+)")
    set(owner ${CMAKE_MATCH_1})
  elseif(rel MATCHES "^(common|idl)(/|$)")
    set(owner common)
  elseif(rel MATCHES "^deploy/launcher(/|$)")
    set(owner launcher)
  elseif(rel MATCHES "^tests(/|$)")
    set(owner tests)
  endif()
  set(${out_var} "${owner}" PARENT_SCOPE)
endfunction()

# <out_var> = the targets `target` links directly (LINK_LIBRARIES and INTERFACE_LINK_LIBRARIES),
# aliases resolved; items that are not targets (paths, flags, conditional expressions) left out.
function(_climbsim_linked_targets target out_var)
  set(found "")
  get_target_property(type ${target} TYPE)
  set(items "")
  if(NOT type STREQUAL "INTERFACE_LIBRARY")
    get_target_property(direct ${target} LINK_LIBRARIES)
    if(direct)
      list(APPEND items ${direct})
    endif()
  endif()
  get_target_property(interface ${target} INTERFACE_LINK_LIBRARIES)
  if(interface)
    list(APPEND items ${interface})
  endif()
  foreach(item IN LISTS items)
    # A static library's private link appears as $<LINK_ONLY:name>; a link made from another
    # directory carries a ::@(directory) marker.
    string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" item "${item}")
    string(REGEX REPLACE "::@\\(.*\\)$" "" item "${item}")
    if(item STREQUAL "" OR item MATCHES "\\$<" OR NOT TARGET "${item}")
      continue()
    endif()
    get_target_property(aliased ${item} ALIASED_TARGET)
    if(aliased)
      set(item ${aliased})
    endif()
    list(APPEND found ${item})
  endforeach()
  list(REMOVE_DUPLICATES found)
  set(${out_var} "${found}" PARENT_SCOPE)
endfunction()

# <out_var> = every target defined in `dir` and its subdirectories.
function(_climbsim_targets_under dir out_var)
  get_property(targets DIRECTORY "${dir}" PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    _climbsim_targets_under("${sub}" more)
    list(APPEND targets ${more})
  endforeach()
  set(${out_var} "${targets}" PARENT_SCOPE)
endfunction()

# Whether a target of `owner` may use what belongs to `used_owner`.
function(_climbsim_may_use owner used_owner out_var)
  if(used_owner STREQUAL "" OR used_owner STREQUAL owner OR used_owner STREQUAL "common")
    set(${out_var} TRUE PARENT_SCOPE)
  else()
    set(${out_var} FALSE PARENT_SCOPE)
  endif()
endfunction()

# The problems of one checked target, one line each, into <out_var>.
function(_climbsim_target_problems target owner out_var)
  set(problems "")
  get_target_property(dir ${target} SOURCE_DIR)
  file(RELATIVE_PATH where "${PROJECT_SOURCE_DIR}" "${dir}")
  set(what "${target} (${where}, owner ${owner})")

  # Links, depth first; `via` remembers how each target was reached.
  set(seen ${target})
  set(todo ${target})
  while(todo)
    list(POP_FRONT todo current)
    _climbsim_linked_targets(${current} linked)
    foreach(used IN LISTS linked)
      if(used IN_LIST seen)
        continue()
      endif()
      list(APPEND seen ${used})
      string(MAKE_C_IDENTIFIER "${current}" current_id)
      string(MAKE_C_IDENTIFIER "${used}" used_id)
      if(current STREQUAL target)
        set(via_${used_id} "")
      else()
        set(via_${used_id} "${via_${current_id}}${current} -> ")
      endif()
      climbsim_owner_of(${used} used_owner)
      _climbsim_may_use("${owner}" "${used_owner}" allowed)
      if(NOT allowed)
        list(APPEND problems "${what} links ${via_${used_id}}${used} of ${used_owner}")
      elseif(NOT used_owner STREQUAL "")
        list(APPEND todo ${used})  # outside packages are not followed
      endif()
    endforeach()
  endwhile()

  # Sources and include directories in another service's folder.
  get_target_property(type ${target} TYPE)
  set(paths "")
  if(NOT type STREQUAL "INTERFACE_LIBRARY")
    get_target_property(sources ${target} SOURCES)
    foreach(source IN LISTS sources)
      if(NOT source MATCHES "\\$<")
        get_filename_component(source "${source}" ABSOLUTE BASE_DIR "${dir}")
        list(APPEND paths "compiles;${source}")
      endif()
    endforeach()
    get_target_property(includes ${target} INCLUDE_DIRECTORIES)
    foreach(include IN LISTS includes)
      if(include AND NOT include MATCHES "\\$<")
        list(APPEND paths "includes;${include}")
      endif()
    endforeach()
  endif()
  while(paths)
    list(POP_FRONT paths verb path)
    string(FIND "${path}" "${CMAKE_BINARY_DIR}" in_build)
    if(in_build EQUAL 0)
      continue()  # generated
    endif()
    _climbsim_owner_of_path("${path}" path_owner)
    _climbsim_may_use("${owner}" "${path_owner}" allowed)
    if(NOT allowed)
      file(RELATIVE_PATH rel "${PROJECT_SOURCE_DIR}" "${path}")
      list(APPEND problems "${what} ${verb} ${rel} of ${path_owner}")
    endif()
  endwhile()
  set(${out_var} "${problems}" PARENT_SCOPE)
endfunction()

# Checks the rules above over every target defined under `PROJECT_SOURCE_DIR`; call it at the
# end of the top-level CMakeLists.txt. FATAL_ERROR listing every broken rule.
function(climbsim_check_service_links)
  _climbsim_targets_under("${PROJECT_SOURCE_DIR}" targets)
  set(problems "")
  set(checked 0)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "UTILITY" OR type STREQUAL "GLOBAL_TARGET")
      continue()
    endif()
    climbsim_owner_of(${target} owner)
    if(owner STREQUAL "" OR owner STREQUAL "tests" OR owner IN_LIST CLIMBSIM_COMPOSERS)
      continue()
    endif()
    math(EXPR checked "${checked} + 1")
    _climbsim_target_problems(${target} "${owner}" found)
    list(APPEND problems ${found})
  endforeach()
  if(problems)
    list(JOIN problems "\n  " text)
    message(FATAL_ERROR "Services side by side: a service may link only its own libraries, common/ and "
                        "idl/ (docs/design.md#layout); move what two services share to common/.\n  ${text}")
  endif()
  message(STATUS "Services side by side: ${checked} targets of the services and common checked, "
                 "no service links another")
endfunction()
