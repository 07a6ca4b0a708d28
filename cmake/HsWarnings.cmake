# hs_set_warnings(target): the project's warning set for its own code.
# Third-party headers come in through imported targets, which CMake marks
# SYSTEM, so these flags only judge our sources.
function(hs_set_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wshadow=local -Wnon-virtual-dtor -Wcast-align
    -Wunused -Woverloaded-virtual -Wnull-dereference -Wdouble-promotion
    -Wformat=2 -Wimplicit-fallthrough
    # GCC 12 reports -Wrestrict on std::string concatenation at -O2
    # (GCC bug 105329), a false positive.
    -Wno-restrict)
endfunction()
