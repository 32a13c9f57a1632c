# Warnings for project targets only (third-party headers come in as SYSTEM includes).
function(palpa_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual
    -Wdouble-promotion -Wimplicit-fallthrough)
  if(PALPA_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
