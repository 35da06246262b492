# Finds the Debian-packaged dependencies (scripts/install-deps.sh installs them): the core
# library's always, the others only for the parts that are built.

find_package(glm CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(hwy CONFIG REQUIRED)
# Highway targets left out of this build besides SSSE3: an expression of HWY_* bits such as
# "HWY_AVX2|HWY_SSE4". Every translation unit sees the same HWY_TARGETS, so the dispatch tables
# and the per-target kernels agree, and a target left out is reported as not available. The
# sanitizer preset uses it: the kernels' compile time grows with the number of targets, and the
# sanitizers multiply it.
# SSSE3 is never compiled: no CPU that lacks SSE4 is tested, and the portable target serves
# one; every x86 target compiled can be forced (TESSERA_SIMD) and so is tested.
set(TESSERA_HWY_DISABLED_TARGETS "" CACHE STRING "Highway targets not to compile (HWY_* bits)")
set(_hwy_disabled "HWY_SSSE3")
if(TESSERA_HWY_DISABLED_TARGETS)
  string(APPEND _hwy_disabled "|${TESSERA_HWY_DISABLED_TARGETS}")
endif()
# Translation units that must leave out more targets (setup_kernel.cpp) add to
# TESSERA_HWY_DISABLED_TARGETS_EXPR rather than replace it.
# These are directory properties of Tessera's top directory, inherited by its subdirectories:
# every Tessera translation unit (libraries, tests, benchmarks, samples) gets them and nothing
# outside Tessera does, since a parent project's directories do not inherit from a
# subproject's. The public headers do not include Highway, so consumers need none of it.
add_compile_definitions("TESSERA_HWY_DISABLED_TARGETS_EXPR=(${_hwy_disabled})"
                        "HWY_DISABLED_TARGETS=TESSERA_HWY_DISABLED_TARGETS_EXPR")
# The portable target (EMU128) beside the SIMD ones everywhere. Highway leaves out targets below
# the compiler's baseline, which on Arm is NEON, so without this an Arm build has no scalar
# kernels to force (SimdTarget::kScalar) and compare with NEON and SVE. On x86-64 the baseline
# is below SSE4 and every attainable target is compiled already.
if(NOT CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64|i[3-6]86)$")
  add_compile_definitions(HWY_COMPILE_ALL_ATTAINABLE)
endif()

if(TESSERA_BUILD_IO)
  find_package(assimp CONFIG REQUIRED)
  # Debian 12's OpenImageIO targets refer to its command-line tools (/usr/bin/iconvert and
  # others), which must exist for the package to load, so scripts/install-deps.sh installs
  # openimageio-tools too.
  find_package(OpenImageIO CONFIG REQUIRED)
  # Debian 12's OpenImageIO target names /usr/include/opencv4 as an include directory even
  # when OpenCV is not installed, which makes every consumer fail to configure. Tessera uses
  # no OpenCV, so the imported targets' interfaces (in Tessera's directories) lose that
  # directory before tessera_io links them.
  foreach(_oiio_target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
    get_target_property(_dirs ${_oiio_target} INTERFACE_INCLUDE_DIRECTORIES)
    if(_dirs)
      list(FILTER _dirs EXCLUDE REGEX "opencv")
      set_property(TARGET ${_oiio_target} PROPERTY INTERFACE_INCLUDE_DIRECTORIES "${_dirs}")
    endif()
    get_target_property(_sys ${_oiio_target} INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    if(_sys)
      list(FILTER _sys EXCLUDE REGEX "opencv")
      set_property(TARGET ${_oiio_target} PROPERTY INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${_sys}")
    endif()
  endforeach()
endif()
if(TESSERA_BUILD_SAMPLES OR TESSERA_BUILD_BENCHMARKS)
  find_package(CLI11 CONFIG REQUIRED)
endif()
if(TESSERA_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(TESSERA_BUILD_BENCHMARKS)
  find_package(benchmark CONFIG REQUIRED)
endif()
