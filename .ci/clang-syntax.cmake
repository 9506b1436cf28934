# Writes one Clang 14 syntax-only command per file of a compile_commands.json, for .ci/clang-syntax:
#   cmake -DDATABASE=build/dev/compile_commands.json -DOUT=commands.txt -P .ci/clang-syntax.cmake
# Each command is the build's own (defines, include paths, standard) with the compiler swapped
# for clang++ and no output; GCC-only warning options are ignored and warnings are not errors (the
# promise is that the kit compiles with Clang; its warnings are the GCC build's business).
cmake_policy(VERSION 3.25)
file(READ "${DATABASE}" database)
string(JSON count LENGTH "${database}")
math(EXPR last "${count} - 1")
set(lines "")

# Appends to `lines` the check of `file` with the database's `command`, which compiles `entry`.
function(springlab_clang_line directory command entry file)
  separate_arguments(arguments UNIX_COMMAND "${command}")
  list(POP_FRONT arguments)  # the compiler
  set(kept "")
  set(skip_next OFF)
  set(include_next OFF)
  foreach(argument IN LISTS arguments)
    if(skip_next)
      set(skip_next OFF)
    elseif(argument STREQUAL "-o" OR argument STREQUAL "-MF" OR argument STREQUAL "-MT")
      set(skip_next ON)
    elseif(argument STREQUAL "-include")
      set(include_next ON)
    elseif(include_next)
      # GCC's precompiled header (SPRINGLAB_PCH) is not Clang's: each file is checked as written,
      # which also shows that it includes what it uses.
      set(include_next OFF)
      if(NOT argument MATCHES "cmake_pch\\.hxx$")
        list(APPEND kept "'-include'" "'${argument}'")
      endif()
    elseif(argument STREQUAL entry)
      list(APPEND kept "'${file}'")
    elseif(NOT argument MATCHES "^(-c|-MD|-flto.*|-fno-fat-lto-objects|-Werror|-Winvalid-pch)$")
      string(REPLACE "'" "'\\''" argument "${argument}")
      list(APPEND kept "'${argument}'")
    endif()
  endforeach()
  list(JOIN kept " " kept)
  string(APPEND lines "cd '${directory}' && clang++ -fsyntax-only -Wno-unknown-warning-option "
                      "-Wno-error ${kept}\n")
  set(lines "${lines}" PARENT_SCOPE)
endfunction()

set(seen "")
foreach(i RANGE ${last})
  string(JSON entry GET "${database}" ${i} file)
  string(JSON directory GET "${database}" ${i} directory)
  string(JSON command GET "${database}" ${i} command)
  # A file compiled in several namespaces (each reference file in up to six, implementations.cmake)
  # differs only in the namespace's name, SPRINGLAB_IMPL: checked once (issue 27: 230 -> 181
  # checks). Any other difference (the implementation table's own definitions) is checked apart.
  string(REGEX REPLACE " -o [^ ]+" "" same "${command}")
  string(REGEX REPLACE "-DSPRINGLAB_IMPL=[A-Za-z0-9_]+" "" same "${same}")
  string(MD5 same "${entry} ${same}")
  if(same IN_LIST seen)
    continue()
  endif()
  list(APPEND seen ${same})
  # A unity file (SPRINGLAB_UNITY) stands for the sources it includes: each is checked alone, with
  # the unity file's flags, as it is compiled when unity files are off.
  set(files "${entry}")
  if(entry MATCHES "/Unity/unity_[0-9]+_cxx\\.cxx$")
    file(STRINGS "${entry}" files REGEX "^#include \"")
    list(TRANSFORM files REPLACE "^#include \"(.*)\"$" "\\1")
  endif()
  foreach(file IN LISTS files)
    if(NOT file MATCHES "/tests/grader/hostile/|/tests/fuzz/|/build/")
      springlab_clang_line("${directory}" "${command}" "${entry}" "${file}")
    endif()
  endforeach()
endforeach()
file(WRITE "${OUT}" "${lines}")
