# Where the reference code (the solutions) comes from. SPRINGLAB_REFERENCE_FROM is one of
#   source    the kit's own repository: solutions/ is here and compiled like any other code;
#   prebuilt  a student release (`./lab release`): no solutions/, but their objects, compiled
#             once by the instructor, in prebuilt/reference/libspringlab_reference.a, with a
#             manifest of the compiler, architecture and files they were made for;
#   student   a student release on another compiler, system or architecture: the student's
#             own files stand in for the reference, and comparisons with it are off.
# SPRINGLAB_SOLUTION_FILES lists the reference's files, as task1_two_masses/spring_damper.cpp.
set(SPRINGLAB_PREBUILT_DIR "${PROJECT_SOURCE_DIR}/prebuilt/reference")
set(SPRINGLAB_PREBUILT_ARCHIVE "${SPRINGLAB_PREBUILT_DIR}/libspringlab_reference.a")
set(SPRINGLAB_PREBUILT_MANIFEST "${SPRINGLAB_PREBUILT_DIR}/manifest.txt")

string(REGEX MATCH "^[0-9]+" _springlab_compiler_major "${CMAKE_CXX_COMPILER_VERSION}")
# What must match for objects made elsewhere to link and run here: the compiler (its major
# version: GCC and Clang keep their C++ ABI within one), the system, the processor, and Eigen,
# whose inline code is compiled into the objects.
set(SPRINGLAB_PLATFORM
    "compiler = ${CMAKE_CXX_COMPILER_ID} ${_springlab_compiler_major}"
    "system = ${CMAKE_SYSTEM_NAME}"
    "architecture = ${CMAKE_SYSTEM_PROCESSOR}"
    "eigen = ${Eigen3_VERSION}")

# The name of a reference object inside the archive: its namespace and its file.
function(springlab_archive_member out ns rel)
  string(REPLACE "/" "__" flat "${rel}")
  string(REGEX REPLACE "\\.cpp$" ".o" flat "${flat}")
  set(${out} "${ns}__${flat}" PARENT_SCOPE)
endfunction()

if(EXISTS "${PROJECT_SOURCE_DIR}/solutions")
  set(SPRINGLAB_REFERENCE_FROM source)
  file(GLOB SPRINGLAB_SOLUTION_FILES CONFIGURE_DEPENDS
       RELATIVE "${PROJECT_SOURCE_DIR}/solutions" "${PROJECT_SOURCE_DIR}/solutions/task*/*.cpp")
elseif(NOT EXISTS "${SPRINGLAB_PREBUILT_MANIFEST}")
  message(FATAL_ERROR "springlab: neither solutions/ nor ${SPRINGLAB_PREBUILT_MANIFEST} is here, "
          "so there is no reference code to build with: this copy of the kit is incomplete "
          "(clone the release again, or ask your instructor)")
else()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${SPRINGLAB_PREBUILT_MANIFEST}"
               "${SPRINGLAB_PREBUILT_ARCHIVE}")
  file(STRINGS "${SPRINGLAB_PREBUILT_MANIFEST}" manifest)
  set(mismatch "")
  foreach(line IN LISTS SPRINGLAB_PLATFORM)
    string(REGEX MATCH "^[a-z]+ = " key "${line}")
    set(found "")
    foreach(made IN LISTS manifest)
      if(made MATCHES "^${key}")
        set(found "${made}")
      endif()
    endforeach()
    if(NOT found STREQUAL line)
      string(REPLACE " = " " " here "${line}")
      string(REPLACE " = " " " there "${found}")
      list(APPEND mismatch "made for ${there}, this is ${here}")
    endif()
  endforeach()
  set(SPRINGLAB_SOLUTION_FILES "")
  foreach(line IN LISTS manifest)
    if(line MATCHES "^file = (.+)$")
      list(APPEND SPRINGLAB_SOLUTION_FILES "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  if(mismatch STREQUAL "")
    set(SPRINGLAB_REFERENCE_FROM prebuilt)
    set(SPRINGLAB_PREBUILT_OBJECTS "${CMAKE_BINARY_DIR}/prebuilt-reference")
    file(REMOVE_RECURSE "${SPRINGLAB_PREBUILT_OBJECTS}")
    file(MAKE_DIRECTORY "${SPRINGLAB_PREBUILT_OBJECTS}")
    execute_process(COMMAND "${CMAKE_AR}" x "${SPRINGLAB_PREBUILT_ARCHIVE}"
                    WORKING_DIRECTORY "${SPRINGLAB_PREBUILT_OBJECTS}" RESULT_VARIABLE failed)
    if(failed)
      message(FATAL_ERROR "springlab: cannot unpack ${SPRINGLAB_PREBUILT_ARCHIVE} (${failed})")
    endif()
  else()
    set(SPRINGLAB_REFERENCE_FROM student)
    list(JOIN mismatch "; " mismatch)
    # Said at the first configuration only: the build's messages stay readable afterwards.
    if(NOT SPRINGLAB_FALLBACK_SAID STREQUAL mismatch)
      message(WARNING "springlab: the reference code in prebuilt/ cannot be used here (${mismatch})."
              "\nYour own code stands in for the reference: each task is tested with your code for "
              "the other tasks too, and the viewer cannot compare with the reference. Everything "
              "else works. To test against the reference, build on the system your instructor "
              "named, or ask for a release made with this compiler.")
      set(SPRINGLAB_FALLBACK_SAID "${mismatch}" CACHE INTERNAL "")
    endif()
  endif()
endif()
list(SORT SPRINGLAB_SOLUTION_FILES)

# The archive a release carries: every reference object the kit compiles (each file in each
# namespace it is built in), made by `./lab release` with the reference-archive preset.
function(springlab_reference_archive)
  if(NOT SPRINGLAB_REFERENCE_FROM STREQUAL "source")
    return()
  endif()
  set(out "${CMAKE_BINARY_DIR}/prebuilt/reference")
  get_property(objects GLOBAL PROPERTY SPRINGLAB_REFERENCE_OBJECTS)
  set(script "file(REMOVE_RECURSE \"${out}\")\nfile(MAKE_DIRECTORY \"${out}/objects\")\n")
  if(SPRINGLAB_IPO)
    set(script "message(FATAL_ERROR \"the reference archive needs SPRINGLAB_LTO=OFF (the "
               "reference-archive preset): link-time optimised objects do not travel\")\n")
  endif()
  set(members "")
  set(targets "")
  foreach(entry IN LISTS objects)
    string(REPLACE "|" ";" entry "${entry}")
    list(GET entry 0 target)
    list(GET entry 1 member)
    string(APPEND script "file(COPY_FILE \"$<TARGET_OBJECTS:${target}>\" \"${out}/objects/${member}\")\n")
    list(APPEND members "${member}")
    list(APPEND targets ${target})
  endforeach()
  set(manifest "# The reference objects of a springlab release: made for this platform only.")
  foreach(line IN LISTS SPRINGLAB_PLATFORM)
    string(APPEND manifest "\n${line}")
  endforeach()
  # For the reader only (not compared): the exact compiler, the build type and its flags.
  string(STRIP "${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_RELWITHDEBINFO}" flags)
  string(APPEND manifest "\ncompiler_version = ${CMAKE_CXX_COMPILER_VERSION}"
                         "\nbuild_type = ${CMAKE_BUILD_TYPE}\nflags = ${flags}")
  foreach(rel IN LISTS SPRINGLAB_SOLUTION_FILES)
    string(APPEND manifest "\nfile = ${rel}")
  endforeach()
  string(APPEND script
    "execute_process(COMMAND \"${CMAKE_AR}\" qc \"${out}/libspringlab_reference.a\" ${members}\n"
    "                WORKING_DIRECTORY \"${out}/objects\" COMMAND_ERROR_IS_FATAL ANY)\n"
    # Debug information would name the instructor's folders, and students never step into it;
    # of the symbols, only what linking needs is kept (no file names, no local ones).
    "execute_process(COMMAND \"${CMAKE_STRIP}\" --strip-unneeded \"${out}/libspringlab_reference.a\" COMMAND_ERROR_IS_FATAL ANY)\n"
    "execute_process(COMMAND \"${CMAKE_RANLIB}\" \"${out}/libspringlab_reference.a\" COMMAND_ERROR_IS_FATAL ANY)\n"
    "file(REMOVE_RECURSE \"${out}/objects\")\n"
    "file(WRITE \"${out}/manifest.txt\" [==[${manifest}\n]==])\n")
  file(GENERATE OUTPUT "${CMAKE_BINARY_DIR}/reference_archive.cmake" CONTENT "${script}")
  add_custom_target(springlab-reference-archive
                    COMMAND "${CMAKE_COMMAND}" -P "${CMAKE_BINARY_DIR}/reference_archive.cmake"
                    COMMENT "The reference's objects for a student release: ${out}")
  add_dependencies(springlab-reference-archive ${targets})
endfunction()
