# invasim's own glue: locate the Debian system packages the project builds against and stop
# with a message naming the Debian package to install when one is missing. No outside code.

# invasim_require(<cmake package> <debian package> [extra find_package args...])
macro(invasim_require cmake_name debian_name)
  find_package(${cmake_name} ${ARGN} QUIET)
  if(NOT ${cmake_name}_FOUND)
    message(FATAL_ERROR
      "invasim needs ${cmake_name}, which was not found.\n"
      "Install the Debian package: apt-get install ${debian_name}")
  endif()
endmacro()

invasim_require(Eigen3 libeigen3-dev NO_MODULE)
# Reading the VTK XML snapshots (.vtp, .pvd).
invasim_require(pugixml libpugixml-dev CONFIG)
# JSON values and files (params.json, summary.json, the sweep workspaces); header-only.
invasim_require(nlohmann_json nlohmann-json3-dev CONFIG)
# CRC-32 of checkpoint files.
invasim_require(ZLIB zlib1g-dev)

find_package(OpenMP QUIET)
if(NOT OpenMP_CXX_FOUND)
  message(FATAL_ERROR "invasim needs OpenMP for C++ (it comes with g++: apt-get install g++)")
endif()

# Lua 5.4: Debian ships headers in /usr/include/lua5.4 and liblua5.4.so.
find_path(LUA54_INCLUDE_DIR lua.h PATHS /usr/include/lua5.4 NO_DEFAULT_PATH)
find_library(LUA54_LIBRARY NAMES lua5.4 liblua5.4)
if(NOT LUA54_INCLUDE_DIR OR NOT LUA54_LIBRARY)
  message(FATAL_ERROR "invasim needs Lua 5.4. Install the Debian package: apt-get install liblua5.4-dev")
endif()
add_library(invasim_lua54 INTERFACE)
target_include_directories(invasim_lua54 SYSTEM INTERFACE ${LUA54_INCLUDE_DIR})
target_link_libraries(invasim_lua54 INTERFACE ${LUA54_LIBRARY})

# CGAL is header-only on Debian 12 but links gmp/mpfr through its CMake config.
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
invasim_require(CGAL libcgal-dev)

if(BUILD_TESTING)
  invasim_require(Catch2 catch2)
  if(NOT Catch2_VERSION VERSION_LESS 3)
    message(FATAL_ERROR "invasim's tests use Catch2 v2 (catch2/catch.hpp); found ${Catch2_VERSION}. "
                        "Install Debian 12's package: apt-get install catch2")
  endif()
endif()
