# Finds every third-party package (all from Debian 12) and repairs what
# Debian's CMake configs get wrong.

find_package(Qt6 6.4 REQUIRED COMPONENTS Core Gui Widgets OpenGL OpenGLWidgets Test Concurrent)
find_package(glm REQUIRED)
find_package(assimp REQUIRED)
find_package(draco REQUIRED)  # KHR_draco_mesh_compression in 3D Tiles content (mesh/gltf_geometry.cpp)
find_package(OpenImageIO REQUIRED)
find_package(SQLite3 REQUIRED)
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
# Colour management (LUTs, scene/color_lut.h): libopencolorio-dev 2.1.
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET OpenColorIO)

# Debian's OpenImageIO 2.4 config lists /usr/include/opencv4 among its include
# directories although libopenimageio-dev does not depend on OpenCV; CMake
# refuses a non-existent path. Keep only the directories that exist.
foreach(_target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${_target})
    get_target_property(_dirs ${_target} INTERFACE_INCLUDE_DIRECTORIES)
    if(_dirs)
      set(_existing "")
      foreach(_d IN LISTS _dirs)
        if(EXISTS "${_d}" OR _d MATCHES "^\\$<")
          list(APPEND _existing "${_d}")
        endif()
      endforeach()
      set_target_properties(${_target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_existing}")
    endif()
  endif()
endforeach()
