# Install rules (TESSERA_INSTALL, on when Tessera is the top-level project): the libraries, the
# public headers (the targets' header file sets: engine/include/tessera and the generated
# version.hpp, never the internal headers of engine/src, simd or binning), the CMake package
# (find_package(Tessera), targets Tessera::tessera and Tessera::io) and pkg-config files.
# `cmake --install BUILD --prefix DIR` puts them under DIR; tests/package proves it.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(TESSERA_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/Tessera"
    CACHE STRING "Where the CMake package files go, relative to the install prefix")
mark_as_advanced(TESSERA_INSTALL_CMAKEDIR)

get_target_property(_tessera_type tessera TYPE)
if(_tessera_type STREQUAL "SHARED_LIBRARY")
  set(TESSERA_SHARED ON)
else()
  set(TESSERA_SHARED OFF)
endif()

# The core and io parts are separate export sets, so that a consumer that asks for the core
# only loads nothing of Assimp and OpenImageIO.
install(TARGETS tessera EXPORT TesseraTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  FILE_SET HEADERS DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT TesseraTargets
  NAMESPACE Tessera::
  DESTINATION ${TESSERA_INSTALL_CMAKEDIR})
if(TARGET tessera_io)
  install(TARGETS tessera_io EXPORT TesseraIoTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    FILE_SET HEADERS DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT TesseraIoTargets
    NAMESPACE Tessera::
    DESTINATION ${TESSERA_INSTALL_CMAKEDIR})
endif()

configure_package_config_file(
  ${PROJECT_SOURCE_DIR}/cmake/TesseraConfig.cmake.in
  ${PROJECT_BINARY_DIR}/TesseraConfig.cmake
  INSTALL_DESTINATION ${TESSERA_INSTALL_CMAKEDIR})
# Any 0.x release accepts a request for another 0.x at or below it, as the soname
# (libtessera.so.0) does.
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/TesseraConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/TesseraConfig.cmake
  ${PROJECT_BINARY_DIR}/TesseraConfigVersion.cmake
  DESTINATION ${TESSERA_INSTALL_CMAKEDIR})

# pkg-config: tessera (the core) and tessera-io. The prefix is found from the .pc file's own
# place (${pcfiledir}), so an install moved or made with --prefix still finds its files. A
# static library's dependencies are in Requires, since `pkg-config --libs` without --static
# must link them; a shared one's are Requires.private.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}" OR IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  message(FATAL_ERROR "TESSERA_INSTALL needs CMAKE_INSTALL_LIBDIR and CMAKE_INSTALL_INCLUDEDIR "
                      "relative to the prefix (the pkg-config files are relocatable)")
endif()
file(RELATIVE_PATH TESSERA_PC_PREFIX "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
string(REGEX REPLACE "/$" "" TESSERA_PC_PREFIX "${TESSERA_PC_PREFIX}")
if(TESSERA_SHARED)
  set(TESSERA_PC_REQUIRES "glm")
  set(TESSERA_PC_REQUIRES_PRIVATE "tbb libhwy")
  set(TESSERA_IO_PC_REQUIRES "tessera")
  set(TESSERA_IO_PC_REQUIRES_PRIVATE "assimp OpenImageIO")
else()
  set(TESSERA_PC_REQUIRES "glm tbb libhwy")
  set(TESSERA_PC_REQUIRES_PRIVATE "")
  set(TESSERA_IO_PC_REQUIRES "tessera assimp OpenImageIO")
  set(TESSERA_IO_PC_REQUIRES_PRIVATE "")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/tessera.pc.in ${PROJECT_BINARY_DIR}/tessera.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/tessera.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
if(TARGET tessera_io)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/tessera-io.pc.in ${PROJECT_BINARY_DIR}/tessera-io.pc
                 @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/tessera-io.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endif()
