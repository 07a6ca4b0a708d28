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

# hs_expose_header_files(target folder header...)
#
# Like hs_expose_headers, for a library with an inside: only the listed
# headers of `folder` are reachable through `target`'s include directory
# (a link per file), the rest of the folder is not. render/ uses it: app/
# and cli/ see the renderer's public headers, not its passes and pools
# (those are for hs_render itself and, through hs_render_internal, for
# tests and benchmarks).
function(hs_expose_header_files target folder)
  set(dir ${PROJECT_BINARY_DIR}/include/${target})
  # A build tree configured before the split has a link to the whole folder
  # here: remove the link (not what it points to) first, or the file links
  # below would be made inside the source folder.
  if(IS_SYMLINK ${dir}/${folder})
    file(REMOVE ${dir}/${folder})
  endif()
  foreach(header IN LISTS ARGN)
    set(link ${dir}/${folder}/${header})
    get_filename_component(parent ${link} DIRECTORY)
    file(MAKE_DIRECTORY ${parent})
    if(NOT IS_SYMLINK ${link})
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder}/${header} ${link} SYMBOLIC)
    endif()
  endforeach()
  target_include_directories(${target} PUBLIC ${dir})
endfunction()
