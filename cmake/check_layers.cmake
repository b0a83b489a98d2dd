# The layers of src/rift (docs/architecture.md section 1): a folder includes only from its own folder
# and from folders of lower layers. Run by the build (target rift_layers) on every build:
#   cmake -DRIFT_SOURCE=<src/rift> -P check_layers.cmake
# An include that runs back up stops the build with the file, line and the edge it broke.
set(layers
  "core"
  "parallel"
  "scene"
  "geometry material fracture"
  "pd mpm"
  "load geomech"
  "hf"
  "io"
  "run")
set(rank 0)
foreach(layer IN LISTS layers)
  string(REPLACE " " ";" folders "${layer}")
  foreach(folder IN LISTS folders)
    set(rank_of_${folder} ${rank})
  endforeach()
  math(EXPR rank "${rank} + 1")
endforeach()

file(GLOB_RECURSE sources RELATIVE ${RIFT_SOURCE} ${RIFT_SOURCE}/*.hpp ${RIFT_SOURCE}/*.cpp ${RIFT_SOURCE}/*.hpp.in)
set(broken "")
foreach(source IN LISTS sources)
  string(REGEX MATCH "^[a-z_]+" from "${source}")
  if(NOT DEFINED rank_of_${from})
    string(APPEND broken "\n  src/rift/${source}: the folder ${from}/ has no layer (cmake/check_layers.cmake)")
    continue()
  endif()
  file(STRINGS ${RIFT_SOURCE}/${source} includes REGEX "^#include \"rift/[a-z_]+/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"rift/([a-z_]+)/.*" "\\1" to "${line}")
    if(to STREQUAL from)
      continue()
    endif()
    if(NOT DEFINED rank_of_${to} OR NOT rank_of_${to} LESS rank_of_${from})
      string(APPEND broken "\n  src/rift/${source}: ${line} (${from}/ may include only lower layers)")
    endif()
  endforeach()
endforeach()
if(broken)
  list(JOIN layers " < " order)
  message(FATAL_ERROR "includes that run against the layers (${order}):${broken}")
endif()
