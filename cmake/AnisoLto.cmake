# Link-time optimisation of the programs a user runs (docs/performance.md, "Link-time
# optimisation and the equilibrium's sums in the force pass").
#
# The libraries compile to fat LTO objects: GCC's intermediate code beside the usual machine code.
# The five stage programs and the benchmarks link with -flto and optimise across files (the DEM
# force pass then inlines the contact law and the exact sums, which live in other files: the step
# 4% faster, the same bits). The tests link the machine code, so the suite's hundred links do not
# each pay for a whole-program optimisation, and the benchmarks are built only on request
# (tests/perf). GCC, Release builds only; off: -DANISO_LTO=OFF.
option(ANISO_LTO "Link-time optimisation of the stage programs and benchmarks (GCC, Release)" ON)
set(ANISO_LTO_ACTIVE OFF)
if(ANISO_LTO AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  set(ANISO_LTO_ACTIVE ON)
endif()

# A library whose code the programs optimise across: intermediate code beside the machine code.
function(aniso_lto_library target)
  if(ANISO_LTO_ACTIVE)
    target_compile_options(${target} PRIVATE "$<$<CONFIG:Release>:-flto=auto;-ffat-lto-objects>")
  endif()
endfunction()

# A program linked with link-time optimisation over its own code and its libraries'.
function(aniso_lto_program target)
  if(ANISO_LTO_ACTIVE)
    target_compile_options(${target} PRIVATE "$<$<CONFIG:Release>:-flto=auto>")
    target_link_options(${target} PRIVATE "$<$<CONFIG:Release>:-flto=auto>")
  endif()
endfunction()
