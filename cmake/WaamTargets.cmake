# Helpers shared by every waam target: warnings and the one-library-per-module rule.

function(waam_target_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(WAAM_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# waam_module(NAME <name> [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Builds the static library waam_<name> from every .cc below the module folder (recursively),
# with the repository root on the include path so headers are included as "planner/mesh/stl.h".
function(waam_module)
  cmake_parse_arguments(ARG "" "NAME" "PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/*.cc")
  list(FILTER sources EXCLUDE REGEX "/benchmarks/")
  set(target waam_${ARG_NAME})
  if(sources)
    add_library(${target} STATIC ${sources})
    target_include_directories(${target} PUBLIC "${PROJECT_SOURCE_DIR}")
    target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
    waam_target_options(${target})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE "${PROJECT_SOURCE_DIR}")
    target_link_libraries(${target} INTERFACE ${ARG_PUBLIC_DEPS})
  endif()
endfunction()
