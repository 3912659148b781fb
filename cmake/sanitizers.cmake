# FOVRT_SANITIZE=address|thread instruments every target of the build (scripts/sanitize.sh builds
# both into their own folders; docs/sanitizers.md). "address" is AddressSanitizer with
# UndefinedBehaviorSanitizer; any undefined behaviour aborts, so a test that hits it fails.
set(FOVRT_SANITIZE "" CACHE STRING "Instrument the build: '' (none), 'address' (ASan+UBSan) or 'thread' (TSan)")
set_property(CACHE FOVRT_SANITIZE PROPERTY STRINGS "" address thread)

if(FOVRT_SANITIZE STREQUAL "address")
  set(fovrt_sanitize_flags -fsanitize=address,undefined -fno-sanitize-recover=undefined)
elseif(FOVRT_SANITIZE STREQUAL "thread")
  set(fovrt_sanitize_flags -fsanitize=thread)
elseif(NOT FOVRT_SANITIZE STREQUAL "")
  message(FATAL_ERROR "FOVRT_SANITIZE='${FOVRT_SANITIZE}': expected '', 'address' or 'thread'")
endif()

if(fovrt_sanitize_flags)
  add_compile_options(${fovrt_sanitize_flags} -fno-omit-frame-pointer)
  add_link_options(${fovrt_sanitize_flags})
endif()

# Under TSan, TBB's and Embree's loops run on the calling thread only: Debian's TBB is not
# instrumented, so TSan cannot see the synchronisation inside tbb::parallel_for and reports every
# loop body as racing. What is left is what fovrt's own threads do. fovrt_sanitize_executables()
# (called once the whole tree is configured) adds the one file that installs the limit to every
# executable and module of the build, so no program or test can miss it.
function(fovrt_sanitize_executables)
  if(NOT FOVRT_SANITIZE STREQUAL "thread")
    return()
  endif()
  set(dirs ${PROJECT_SOURCE_DIR})
  while(dirs)
    list(POP_FRONT dirs dir)
    get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
    list(APPEND dirs ${subdirs})
    get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target ${targets})
      get_target_property(type ${target} TYPE)
      if(type STREQUAL "EXECUTABLE")
        target_sources(${target} PRIVATE ${PROJECT_SOURCE_DIR}/src/core/tsan_serial_tbb.cpp)
        target_link_libraries(${target} PRIVATE TBB::tbb)
      endif()
    endforeach()
  endwhile()
endfunction()
