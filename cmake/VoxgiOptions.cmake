# Compiler settings shared by every voxgi target.
find_program(CCACHE_PROGRAM ccache)
if(CCACHE_PROGRAM)
  set(CMAKE_CXX_COMPILER_LAUNCHER "${CCACHE_PROGRAM}")
  set(CMAKE_C_COMPILER_LAUNCHER "${CCACHE_PROGRAM}")
endif()

add_library(voxgi_options INTERFACE)
target_compile_options(voxgi_options INTERFACE -Wall -Wextra -Wpedantic -Wno-unused-parameter)
if(VOXGI_WERROR)
  target_compile_options(voxgi_options INTERFACE -Werror)
endif()
if(VOXGI_SANITIZE)
  target_compile_options(voxgi_options INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer)
  target_link_options(voxgi_options INTERFACE -fsanitize=address,undefined)
endif()

# Every voxgi library: sources found per folder so a new file needs no CMake edit.
function(voxgi_library name)
  cmake_parse_arguments(ARG "" "" "DIRS;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  set(sources)
  foreach(dir IN LISTS ARG_DIRS)
    file(GLOB_RECURSE found CONFIGURE_DEPENDS "${dir}/*.cpp")
    list(APPEND sources ${found})
  endforeach()
  add_library(${name} STATIC ${sources})
  target_include_directories(${name} PUBLIC "${PROJECT_SOURCE_DIR}")
  target_link_libraries(${name} PUBLIC voxgi_options ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  target_compile_definitions(${name} PRIVATE
    VOXGI_SHADER_DIR="${VOXGI_SHADER_DIR}" VOXGI_SCENE_DIR="${VOXGI_SCENE_DIR}"
    VOXGI_VERSION="${PROJECT_VERSION}")
endfunction()
