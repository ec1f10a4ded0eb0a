# cmake/SoftmolDependencies.cmake — every third-party dependency, each a Debian 12 package
# installed by scripts/setup.sh. Nothing is vendored.
find_package(Threads REQUIRED)
find_package(glm CONFIG REQUIRED)             # libglm-dev
find_package(TBB CONFIG REQUIRED)             # libtbb-dev
find_package(hwy CONFIG REQUIRED)             # libhwy-dev (Highway 1.0.3)
# libopenimageio-dev: its CMake config names /usr/include/opencv4 (absent without OpenCV),
# so use its pkg-config file instead. Only the module io/softmol_oiio.so links it (start-up:
# OpenImageIO brings ~260 shared libraries into a process).
find_package(PkgConfig REQUIRED)
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
add_library(softmol_oiio INTERFACE)
add_library(softmol::oiio ALIAS softmol_oiio)
target_link_libraries(softmol_oiio INTERFACE PkgConfig::OIIO)
find_package(CLI11 CONFIG REQUIRED)           # libcli11-dev
find_package(nlohmann_json CONFIG REQUIRED)   # nlohmann-json3-dev
find_package(ZLIB REQUIRED)                   # zlib1g-dev (gemmi's gzip input, the PNG encoder)
find_package(PNG REQUIRED)                    # libpng-dev (reading PNG; the bench's reference encoder)

# gemmi-dev is header-only in Debian 12 and ships no CMake config.
find_path(GEMMI_INCLUDE_DIR gemmi/mmread.hpp REQUIRED)
add_library(softmol_gemmi INTERFACE)
add_library(softmol::gemmi ALIAS softmol_gemmi)
target_include_directories(softmol_gemmi SYSTEM INTERFACE ${GEMMI_INCLUDE_DIR})
target_link_libraries(softmol_gemmi INTERFACE ZLIB::ZLIB)

if(SOFTMOL_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)         # libgtest-dev
  include(GoogleTest)
endif()
if(SOFTMOL_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)     # libbenchmark-dev
endif()
