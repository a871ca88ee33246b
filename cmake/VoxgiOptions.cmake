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
if(VOXGI_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "VOXGI_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
  endif()
  target_compile_options(voxgi_options INTERFACE -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -g)
  target_link_options(voxgi_options INTERFACE -fsanitize=address,undefined)
endif()
if(VOXGI_SANITIZE)
  target_compile_options(voxgi_options INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer)
  target_link_options(voxgi_options INTERFACE -fsanitize=address,undefined)
endif()
# The parts that read input and write files (docs/reliability.md): with VOXGI_SANITIZE_INPUT only
# their sources are instrumented and every program links the sanitizer runtimes. The rest (GL,
# the GI methods, OpenVDB-heavy propagation) compiles exactly as in the plain build, so ccache
# serves it and the build takes minutes where a fully sanitized one takes hours.
set(VOXGI_INPUT_DIRS scenes volumes tools gi/pathtrace gi/raytrace gi/metrics gi/sampling)
if(VOXGI_SANITIZE_INPUT)
  target_link_options(voxgi_options INTERFACE -fsanitize=address,undefined)
endif()
function(voxgi_sanitize_input_sources)
  foreach(source IN LISTS ARGN)
    file(RELATIVE_PATH relative "${PROJECT_SOURCE_DIR}" "${source}")
    set(options "")
    if(VOXGI_SANITIZE_INPUT)
      foreach(dir IN LISTS VOXGI_INPUT_DIRS)
        if(relative MATCHES "^${dir}/")
          # Line tables only (-g1): all a sanitizer's stack trace reads, and a third less
          # compile time than -g (tools/cmd_eval.cpp 20 s against 32 s) and half the objects.
          set(options "-fsanitize=address,undefined;-fno-omit-frame-pointer;-g1")
        endif()
      endforeach()
    endif()
    # OpenVDB's templates under the sanitizers compile twice as fast at -O1 as at -O3
    # (volumes/volume_io.cpp: 75 s against 160 s), and volumes/ runs little in the tests. The
    # fuzz build sanitizes everything, so its volumes/ gets -O1 too.
    if((options OR VOXGI_FUZZ) AND relative MATCHES "^volumes/")
      list(APPEND options "-O1")
    endif()
    if(options)
      set_source_files_properties("${source}" PROPERTIES COMPILE_OPTIONS "${options}")
    endif()
  endforeach()
endfunction()

# Every voxgi library: sources found per folder so a new file needs no CMake edit.
function(voxgi_library name)
  cmake_parse_arguments(ARG "" "" "DIRS;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  set(sources)
  foreach(dir IN LISTS ARG_DIRS)
    file(GLOB_RECURSE found CONFIGURE_DEPENDS "${dir}/*.cpp")
    list(APPEND sources ${found})
  endforeach()
  voxgi_sanitize_input_sources(${sources})
  add_library(${name} STATIC ${sources})
  target_include_directories(${name} PUBLIC "${PROJECT_SOURCE_DIR}")
  target_link_libraries(${name} PUBLIC voxgi_options ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  target_compile_definitions(${name} PRIVATE
    VOXGI_SHADER_DIR="${VOXGI_SHADER_DIR}" VOXGI_SCENE_DIR="${VOXGI_SCENE_DIR}"
    VOXGI_VERSION="${PROJECT_VERSION}")
endfunction()
