# Optional peer benchmark: Example 1 with Siconos' Euler-Moreau time stepping.
# Included from CMakeLists.txt after catkin_package(); skipped quietly when Siconos is absent
# (Debian/Ubuntu: libsiconos-kernel-dev).

# The kernel headers include each other and the numerics headers by bare name, and
# SiconosConfig.h sits one level up, so all three directories are needed.
find_path(SICONOS_KERNEL_INCLUDE_DIR SiconosKernel.hpp PATH_SUFFIXES siconos/kernel)
find_path(SICONOS_NUMERICS_INCLUDE_DIR NumericsMatrix.h PATH_SUFFIXES siconos/numerics)
find_path(SICONOS_CONFIG_INCLUDE_DIR SiconosConfig.h PATH_SUFFIXES siconos)
find_library(SICONOS_KERNEL_LIBRARY siconos_kernel)
find_library(SICONOS_NUMERICS_LIBRARY siconos_numerics)
# Event.hpp and TimeDiscretisation.hpp include <gmp.h>; the kernel API uses boost smart pointers.
find_path(SICONOS_GMP_INCLUDE_DIR gmp.h)
find_package(Boost QUIET)

if(SICONOS_KERNEL_INCLUDE_DIR AND SICONOS_NUMERICS_INCLUDE_DIR AND SICONOS_CONFIG_INCLUDE_DIR
   AND SICONOS_KERNEL_LIBRARY AND SICONOS_NUMERICS_LIBRARY AND SICONOS_GMP_INCLUDE_DIR
   AND Boost_FOUND)
  message(STATUS "Siconos found: building siconos_example1")
  add_executable(siconos_example1 bench/siconos_example1.cpp)
  # SYSTEM: the Siconos headers are not -Wall -Wextra clean.
  target_include_directories(siconos_example1 SYSTEM PRIVATE
    ${SICONOS_KERNEL_INCLUDE_DIR}
    ${SICONOS_NUMERICS_INCLUDE_DIR}
    ${SICONOS_CONFIG_INCLUDE_DIR}
    ${SICONOS_GMP_INCLUDE_DIR}
    ${Boost_INCLUDE_DIRS})
  target_link_libraries(siconos_example1 ${SICONOS_KERNEL_LIBRARY} ${SICONOS_NUMERICS_LIBRARY})
  set_target_properties(siconos_example1 PROPERTIES
    CXX_STANDARD 17
    CXX_STANDARD_REQUIRED ON
    RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
else()
  message(STATUS "Siconos not found: the peer benchmark siconos_example1 is skipped")
endif()
