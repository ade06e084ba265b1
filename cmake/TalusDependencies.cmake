# Finds Talus's dependencies and defines the imported targets the layers link.
# Included both by the build and by the installed talusConfig.cmake, so a
# downstream project re-finds exactly what the installed libraries need.
include(CMakeFindDependencyMacro)

find_dependency(Eigen3 3.4 NO_MODULE)

# nlohmann_json (header-only): summary.json and the sweep engine's parameters and records
# (talus::core's public headers under report/ and sweep/).
find_dependency(nlohmann_json 3.11 CONFIG)

# SuiteSparse 5.12 (Debian 12) ships neither CMake configs nor .pc files.
if(NOT TARGET SuiteSparse::CHOLMOD)
  find_path(SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
  foreach(_talus_ss cholmod suitesparseconfig)
    find_library(SUITESPARSE_${_talus_ss}_LIBRARY NAMES ${_talus_ss} REQUIRED)
  endforeach()
  add_library(SuiteSparse::CHOLMOD INTERFACE IMPORTED)
  target_include_directories(SuiteSparse::CHOLMOD SYSTEM INTERFACE ${SUITESPARSE_INCLUDE_DIR})
  target_link_libraries(SuiteSparse::CHOLMOD INTERFACE ${SUITESPARSE_cholmod_LIBRARY}
                                                      ${SUITESPARSE_suitesparseconfig_LIBRARY})
endif()

# BLAS and LAPACK (OpenBLAS on Debian 12; CHOLMOD links them too): the dense
# per-axis eigenvectors and products of the smoothing fit's solver (talus::bspline).
find_dependency(BLAS)
find_dependency(LAPACK)

# Ipopt 3.11 has only a pkg-config file; its flags carry -DHAVE_CSTDDEF, which
# IpSmartPtr.hpp needs.
find_dependency(PkgConfig)
if(NOT TARGET PkgConfig::IPOPT)
  pkg_check_modules(IPOPT REQUIRED IMPORTED_TARGET GLOBAL ipopt>=3.11)
endif()

# Two NLopt packages exist on Debian; only this one has the C++ target.
find_dependency(NLopt 2.7 CONFIG HINTS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/nlopt_cxx)

find_dependency(SUNDIALS 6.4 CONFIG COMPONENTS cvode)

# Vehicle files (dynamics) and robot files (kinematic). The 0.7 target is plain `yaml-cpp` (namespaced from 0.8 on).
find_dependency(yaml-cpp 0.7 CONFIG)

# OMPL 1.5 (Reeds–Shepp curves of the kinematic planners). Its config sets
# variables only; wrap them in an imported target. Only OMPL's own include
# directory is used: the config also lists /usr/include, which as a SYSTEM
# directory would break libstdc++'s #include_next.
find_dependency(ompl 1.5 CONFIG)
if(NOT TARGET OMPL::OMPL)
  add_library(OMPL::OMPL INTERFACE IMPORTED)
  target_include_directories(OMPL::OMPL SYSTEM INTERFACE ${OMPL_INCLUDE_DIR})
  target_link_libraries(OMPL::OMPL INTERFACE ${OMPL_LIBRARIES})
endif()
