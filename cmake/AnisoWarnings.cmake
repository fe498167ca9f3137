# Warnings on for our code only; third-party headers come in as SYSTEM.
add_library(aniso_warnings INTERFACE)
target_compile_options(aniso_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                                -Wno-sign-conversion -Wnon-virtual-dtor -Wold-style-cast)
# GCC 12 reports -Wrestrict inside libstdc++'s std::string concatenation at -O2
# (GCC bug 105329, a false positive); it would stop -Werror builds.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_GREATER_EQUAL 12)
  target_compile_options(aniso_warnings INTERFACE -Wno-restrict)
endif()
if(ANISO_WERROR)
  target_compile_options(aniso_warnings INTERFACE -Werror)
endif()

add_library(aniso_arch INTERFACE)
if(ANISO_NATIVE)
  target_compile_options(aniso_arch INTERFACE -march=native)
endif()
