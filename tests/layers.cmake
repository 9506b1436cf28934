# The core's layers (handout/maintainers.md, "The core, layer by layer"), checked: a file of
# common/ includes headers of its own layer or lower ones, never higher. Sources sit in a folder
# per layer (common/src/<layer>/); public headers are listed here by layer. Run by CTest
# (core.layers) as cmake -DROOT=<kit> -P tests/layers.cmake: each include that runs back up a
# layer is printed with both layers, and the test fails.
cmake_minimum_required(VERSION 3.25)
set(layers support scenes model integrators stability simulation diagnosis)
# The public headers of each layer (common/include/springlab/); a new header must be added here.
set(headers_support types errors todo task_api parallel avx2 real_text eigen_solvers)
set(headers_scenes parameters selection scene_text scene_file builtin_scenes memory_budget
    cli_values progress)
set(headers_model task1_two_masses task2_four_masses task3_shear_springs task4_verlet
    task5_fabric implementation this_implementation wind verlet_support scene grid_forces)
set(headers_integrators integrator)
set(headers_stability stability)
set(headers_simulation simulation diagnostics)
set(headers_diagnosis divergence comparison)
# The includes that run up a layer today, each for one function (the maintainers' page says why);
# no other may be added.
set(allowed
    "scenes/parameters.cpp -> integrator.hpp"     # is_integrator_name: a scene names its method
    "simulation/simulation.cpp -> divergence.hpp")  # a run that diverges is diagnosed

function(rank_of_layer name out)
  list(FIND layers "${name}" index)
  set(${out} ${index} PARENT_SCOPE)
endfunction()

# The layer of an included name ("springlab/x.hpp" or a private "support/numbers.hpp").
function(rank_of_include include out)
  set(${out} -1 PARENT_SCOPE)
  if(include MATCHES "^springlab/([a-z0-9_]+)\\.hpp$")
    set(name ${CMAKE_MATCH_1})
    foreach(layer IN LISTS layers)
      if(name IN_LIST headers_${layer})
        rank_of_layer(${layer} rank)
        set(${out} ${rank} PARENT_SCOPE)
        return()
      endif()
    endforeach()
    message(SEND_ERROR "common/include/springlab/${name}.hpp is in no layer: add it to tests/layers.cmake")
  elseif(include MATCHES "^([a-z]+)/[a-z0-9_]+\\.hpp$")
    rank_of_layer(${CMAKE_MATCH_1} rank)
    set(${out} ${rank} PARENT_SCOPE)
  endif()
endfunction()

set(failures 0)
set(checked 0)
file(GLOB_RECURSE files RELATIVE "${ROOT}/common" "${ROOT}/common/src/*.cpp"
     "${ROOT}/common/src/*.hpp" "${ROOT}/common/include/springlab/*.hpp")
foreach(file IN LISTS files)
  if(file MATCHES "^src/([a-z]+)/")
    set(layer ${CMAKE_MATCH_1})
    string(REPLACE "src/" "" short "${file}")
    if(NOT layer IN_LIST layers)
      message(SEND_ERROR "common/${file}: its folder ${layer} is no layer of ${layers}")
      math(EXPR failures "${failures} + 1")
      continue()
    endif()
    rank_of_layer(${layer} rank)
  elseif(file MATCHES "^include/springlab/([a-z0-9_]+)\\.hpp$")
    set(short "${CMAKE_MATCH_1}.hpp")
    rank_of_include("springlab/${short}" rank)
    set(layer "?")
    if(rank GREATER_EQUAL 0)
      list(GET layers ${rank} layer)
    endif()
  else()
    message(SEND_ERROR "common/${file}: a source outside the layers' folders (common/src/<layer>/)")
    math(EXPR failures "${failures} + 1")
    continue()
  endif()
  file(STRINGS "${ROOT}/common/${file}" lines REGEX "^#include \"")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" include "${line}")
    rank_of_include("${include}" included)
    math(EXPR checked "${checked} + 1")
    if(included GREATER rank)
      string(REGEX REPLACE "^.*/" "" included_file "${include}")
      if("${short} -> ${included_file}" IN_LIST allowed)
        continue()
      endif()
      list(GET layers ${included} included_layer)
      message("common/${file} (layer ${layer}) includes ${include} (layer ${included_layer}): "
              "a file may include its own layer or lower ones (${layers}, lowest first)")
      math(EXPR failures "${failures} + 1")
    endif()
  endforeach()
endforeach()
list(LENGTH files count)
if(failures GREATER 0)
  message(FATAL_ERROR "layers: ${failures} includes run up a layer")
endif()
list(LENGTH allowed exceptions)
message("layers: ok: ${count} files of common/, ${checked} includes of the kit's headers, none "
        "up a layer but the ${exceptions} listed")
