# Warnings on for our code only; third-party headers come in as SYSTEM.
add_library(aniso_warnings INTERFACE)
target_compile_options(aniso_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                                -Wno-sign-conversion -Wnon-virtual-dtor -Wold-style-cast)
if(ANISO_WERROR)
  target_compile_options(aniso_warnings INTERFACE -Werror)
endif()

add_library(aniso_arch INTERFACE)
if(ANISO_NATIVE)
  target_compile_options(aniso_arch INTERFACE -march=native)
endif()
