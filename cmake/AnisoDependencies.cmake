# Every dependency comes from a Debian package; when one is missing, say which
# package to install instead of letting CMake print a search path.
function(aniso_missing what package)
  message(FATAL_ERROR "aniso: ${what} not found. Install it with:\n"
                      "  apt-get install ${package}\n"
                      "(or run scripts/install-deps.sh, which installs everything aniso needs)")
endfunction()

find_package(MPI COMPONENTS C CXX QUIET)
if(NOT MPI_FOUND)
  aniso_missing("MPI (Open MPI)" "libopenmpi-dev openmpi-bin")
endif()

# Debian's parallel HDF5 lives in its own prefix; point FindHDF5 at it.
set(HDF5_PREFER_PARALLEL TRUE)
if(NOT HDF5_C_COMPILER_EXECUTABLE AND EXISTS /usr/bin/h5pcc)
  set(HDF5_C_COMPILER_EXECUTABLE /usr/bin/h5pcc)
endif()
find_package(HDF5 COMPONENTS C QUIET)
if(NOT HDF5_FOUND)
  aniso_missing("HDF5 (parallel)" "libhdf5-openmpi-dev hdf5-tools")
endif()
if(NOT HDF5_IS_PARALLEL)
  message(FATAL_ERROR "aniso: the HDF5 found (${HDF5_INCLUDE_DIRS}) is serial; aniso needs the MPI build:\n"
                      "  apt-get install libhdf5-openmpi-dev")
endif()

find_package(PkgConfig QUIET)
if(NOT PkgConfig_FOUND)
  aniso_missing("pkg-config" "pkg-config")
endif()
pkg_check_modules(PETSC QUIET IMPORTED_TARGET PETSc)
if(NOT PETSC_FOUND)
  pkg_check_modules(PETSC QUIET IMPORTED_TARGET petsc)
endif()
if(NOT PETSC_FOUND)
  aniso_missing("PETSc (pkg-config module PETSc)" "petsc-dev")
endif()

find_path(METIS_INCLUDE_DIR metis.h)
find_library(METIS_LIBRARY metis)
if(NOT METIS_INCLUDE_DIR OR NOT METIS_LIBRARY)
  aniso_missing("METIS" "libmetis-dev")
endif()
add_library(aniso::metis INTERFACE IMPORTED)
target_include_directories(aniso::metis INTERFACE ${METIS_INCLUDE_DIR})
target_link_libraries(aniso::metis INTERFACE ${METIS_LIBRARY})

find_package(Eigen3 3.4 QUIET NO_MODULE)
if(NOT Eigen3_FOUND)
  aniso_missing("Eigen 3.4" "libeigen3-dev")
endif()

find_path(CLI11_INCLUDE_DIR CLI/CLI.hpp)
if(NOT CLI11_INCLUDE_DIR)
  aniso_missing("CLI11" "libcli11-dev")
endif()
add_library(aniso::cli11 INTERFACE IMPORTED)
target_include_directories(aniso::cli11 INTERFACE ${CLI11_INCLUDE_DIR})

find_package(tomlplusplus QUIET)
if(NOT tomlplusplus_FOUND)
  aniso_missing("toml++" "libtomlplusplus-dev")
endif()

find_package(fmt QUIET)
if(NOT fmt_FOUND)
  aniso_missing("fmt" "libfmt-dev")
endif()
find_package(spdlog QUIET)
if(NOT spdlog_FOUND)
  aniso_missing("spdlog" "libspdlog-dev")
endif()

if(ANISO_BUILD_TESTS)
  find_package(GTest QUIET)
  if(NOT GTest_FOUND)
    aniso_missing("GoogleTest" "libgtest-dev libgmock-dev")
  endif()
endif()

find_package(Git QUIET)
