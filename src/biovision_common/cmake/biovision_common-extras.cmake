# CMake functions of the ROS-free BioVision libraries (exported by biovision_common).

# biovision_link_core(<target> <package>...)
# Links the ROS-free core libraries of other BioVision packages into <target> without their ROS
# dependencies: a package's catkin <pkg>_LIBRARIES also carries roscpp & co. from its nodelet, which a
# core library must never need. Uses the target when it is built in this CMake run (catkin_make), else
# the package's lib<package>.so.
function(biovision_link_core target)
  foreach(package ${ARGN})
    if(TARGET ${package})
      target_link_libraries(${target} ${package})
    else()
      find_library(${package}_CORE_LIBRARY ${package} PATHS ${${package}_LIBRARY_DIRS} NO_DEFAULT_PATH)
      if(NOT ${package}_CORE_LIBRARY)
        message(FATAL_ERROR "biovision_link_core: no core library of ${package} found")
      endif()
      target_link_libraries(${target} ${${package}_CORE_LIBRARY})
    endif()
  endforeach()
endfunction()
