# Implementation builds (see common/include/springlab/task_api.hpp).
#
# Every task file is compiled into an inline namespace named by SPRINGLAB_IMPL:
#   reference       all of solutions/
#   student_taskN   the student's task N files (tasks/taskN_*) and solutions/ for the other tasks
# so that one program (the runner, the viewer) can hold every build at once and switch between
# them. The grader builds submissions its own way (tests/grader/). Where solutions/ is not here
# (a student release), its objects come prebuilt (common/reference.cmake).

set(SPRINGLAB_TASKS 1 2 3 4 5)

# The task number of a path such as task2_four_masses/spring_forces.cpp.
function(springlab_task_of path out)
  string(REGEX MATCH "^task([0-9]+)_" _ "${path}")
  set(${out} "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()

# An object library for one file, `rel` (as task1_two_masses/spring_damper.cpp) of `tree`
# (solutions or tasks), in one namespace, made once and shared by every build using it.
function(springlab_object out ns tree rel)
  if(tree STREQUAL "solutions" AND SPRINGLAB_REFERENCE_FROM STREQUAL "student")
    set(tree tasks)  # no usable reference: the student's own file stands in
  endif()
  if(tree STREQUAL "solutions")
    set(file "${PROJECT_SOURCE_DIR}/solutions/${rel}")
  else()
    set(file "${SPRINGLAB_TASKS_DIR}/${rel}")
    if(NOT EXISTS "${file}")
      message(FATAL_ERROR "${file} is missing: tasks/ must hold every file of the reference "
              "(${SPRINGLAB_SOLUTION_FILES})")
    endif()
  endif()
  get_filename_component(name "${file}" NAME_WE)
  string(MD5 hash "${tree}/${rel}")
  string(SUBSTRING "${hash}" 0 8 hash)
  string(MAKE_C_IDENTIFIER "obj_${ns}_${name}_${hash}" target)
  set(${out} ${target} PARENT_SCOPE)
  if(TARGET ${target})
    return()
  endif()
  springlab_archive_member(member ${ns} "${rel}")
  if(tree STREQUAL "solutions" AND SPRINGLAB_REFERENCE_FROM STREQUAL "prebuilt")
    add_library(${target} OBJECT IMPORTED)
    set_property(TARGET ${target} PROPERTY IMPORTED_OBJECTS
                 "${SPRINGLAB_PREBUILT_OBJECTS}/${member}")
    return()
  endif()
  add_library(${target} OBJECT "${file}")
  target_compile_definitions(${target} PRIVATE SPRINGLAB_IMPL=${ns})
  target_link_libraries(${target} PRIVATE springlab_core)
  # Position-independent: the grader links the reference into programs of its own, and a
  # release's prebuilt objects must fit every program that uses them.
  set_property(TARGET ${target} PROPERTY POSITION_INDEPENDENT_CODE ON)
  if(tree STREQUAL "solutions")
    target_link_libraries(${target} PRIVATE springlab_warnings)
    set_property(TARGET ${target} PROPERTY INTERPROCEDURAL_OPTIMIZATION ${SPRINGLAB_IPO})
    set_property(GLOBAL APPEND PROPERTY SPRINGLAB_REFERENCE_OBJECTS "${target}|${member}")
  else()  # a student's file: warn, never fail the build; full debug information, to step
    # through it in a debugger (the kit's own code has line tables only, -g1: a third faster
    # to compile, and enough for backtraces and the sanitizers' reports)
    target_compile_options(${target} PRIVATE ${SPRINGLAB_WARNINGS} ${SPRINGLAB_DEBUG_INFO})
    # Eigen's index and size checks (and assert()) stay on in a student's files in every build,
    # as the grader compiles them (tests/grader/CMakeLists.txt): .col(9) of a 2x9 matrix stops
    # with a message (tests/feedback/words.cpp says which check) instead of reading past the end.
    target_compile_options(${target} PRIVATE $<IF:$<CXX_COMPILER_ID:MSVC>,/UNDEBUG,-UNDEBUG>)
  endif()
  set(pch_group solutions)
  if(NOT ns STREQUAL "reference" AND NOT SPRINGLAB_SANITIZE_ALL AND NOT MSVC)
    target_compile_options(${target} PRIVATE -fno-sanitize=undefined)  # see tests/CMakeLists.txt
    set(pch_group solutions_without_ubsan)
  endif()
  if(tree STREQUAL "solutions")
    springlab_share_solutions_pch(${target} ${pch_group})
  endif()
endfunction()

# Build time (issue 27): each reference file is compiled once per namespace (54 objects in the dev
# tree), and parsing Eigen and the standard library was three quarters of each one's time. Objects
# of one group (the same compiler options) share one precompiled header, made by a target of its
# own without a namespace: GCC refuses a header made with another SPRINGLAB_IMPL, but takes one
# made without it, as the headers it holds never read it. GCC only (Clang refuses both).
# GCC takes a precompiled header's optimisation options over the file's own: a reference file
# given options of its own (as the core's -O3 files) must skip it (SKIP_PRECOMPILE_HEADERS).
function(springlab_share_solutions_pch target group)
  if(NOT SPRINGLAB_PCH OR NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    return()
  endif()
  set(owner springlab_pch_${group})
  if(NOT TARGET ${owner})
    add_library(${owner} OBJECT "${PROJECT_SOURCE_DIR}/common/impl/shared_pch.cpp")
    target_link_libraries(${owner} PRIVATE springlab_core springlab_warnings)
    set_property(TARGET ${owner} PROPERTY POSITION_INDEPENDENT_CODE ON)
    set_property(TARGET ${owner} PROPERTY INTERPROCEDURAL_OPTIMIZATION ${SPRINGLAB_IPO})
    if(group STREQUAL "solutions_without_ubsan")
      target_compile_options(${owner} PRIVATE -fno-sanitize=undefined)
    endif()
    target_precompile_headers(${owner} PRIVATE <Eigen/Core> <array> <functional> <limits>
                              <numbers> <stdexcept> <string> <string_view> <vector>)
  endif()
  target_precompile_headers(${target} REUSE_FROM ${owner})
endfunction()

# springlab_add_implementation(TARGET NS STUDENT_TASK): the solutions in namespace NS, with task
# STUDENT_TASK's files taken from SPRINGLAB_TASKS_DIR (0: none, the reference).
function(springlab_add_implementation target ns student_task)
  set(objects "")
  foreach(rel IN LISTS SPRINGLAB_SOLUTION_FILES)
    springlab_task_of("${rel}" task)
    set(tree solutions)
    if(task STREQUAL "${student_task}")
      set(tree tasks)
    endif()
    springlab_object(object ${ns} ${tree} "${rel}")
    list(APPEND objects $<TARGET_OBJECTS:${object}>)
  endforeach()
  add_library(${target} STATIC "${PROJECT_SOURCE_DIR}/common/impl/implementation_table.cpp"
              ${objects})
  # Whether the solutions' files are in it (a student release without its prebuilt reference
  # builds the reference from the student's files).
  set(solutions_inside 1)
  if(SPRINGLAB_REFERENCE_FROM STREQUAL "student")
    set(solutions_inside 0)
  endif()
  target_compile_definitions(${target} PRIVATE SPRINGLAB_IMPL=${ns}
                             SPRINGLAB_STUDENT_TASK=${student_task}
                             SPRINGLAB_SOLUTIONS_INSIDE=${solutions_inside})
  target_link_libraries(${target} PUBLIC springlab_core PRIVATE springlab_warnings)
  # Archived with gcc-ar, which indexes the link-time-optimised objects (see CMakeLists.txt).
  set_property(TARGET ${target} PROPERTY INTERPROCEDURAL_OPTIMIZATION ${SPRINGLAB_IPO})
endfunction()

springlab_add_implementation(springlab_reference reference 0)
foreach(task IN LISTS SPRINGLAB_TASKS)
  springlab_add_implementation(springlab_student_task${task} student_task${task} ${task})
endforeach()

# All builds in one library, for the front ends that choose at run time.
add_library(springlab_implementations STATIC "${PROJECT_SOURCE_DIR}/common/impl/registry.cpp")
target_link_libraries(springlab_implementations PUBLIC springlab_core springlab_reference
                      springlab_student_task1 springlab_student_task2 springlab_student_task3
                      springlab_student_task4 springlab_student_task5 PRIVATE springlab_warnings)
if(SPRINGLAB_REFERENCE_FROM STREQUAL "student")
  target_compile_definitions(springlab_implementations PRIVATE SPRINGLAB_NO_REFERENCE)
endif()
