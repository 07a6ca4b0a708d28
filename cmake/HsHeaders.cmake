# hs_expose_headers(target folder...)
#
# Each library exposes only its own headers (DESIGN.md): code includes
# "<folder>/<header>.h", and the folder is reachable only through the
# include directory of the library that owns it, a directory of its own in
# the build tree holding one link per folder:
#
#   build/include/hs_terrain/terrain -> <source>/terrain
#
# A target sees the folders of the libraries it links (transitively through
# PUBLIC links) and no others, so a library that includes a header of a
# library it does not declare fails to compile. The source root is on no
# include path. tests/layering checks that this holds.
function(hs_expose_headers target)
  set(dir ${PROJECT_BINARY_DIR}/include/${target})
  foreach(folder IN LISTS ARGN)
    get_filename_component(parent ${dir}/${folder} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    if(NOT IS_SYMLINK ${dir}/${folder})
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${dir}/${folder} SYMBOLIC)
    endif()
  endforeach()
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE ${dir})
  elseif(type STREQUAL "EXECUTABLE")
    target_include_directories(${target} PRIVATE ${dir})
  else()
    target_include_directories(${target} PUBLIC ${dir})
  endif()
endfunction()
