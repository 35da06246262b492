# What every Tessera library (tessera, tessera_io) gets: its version, and in a shared build the
# soname and hidden symbols.

# libtessera.so.0.1.0 with the soname libtessera.so.0: SOVERSION is the major version, 0 for
# now. Static builds ignore both.
# Shared builds export only the declarations marked TESSERA_API (tessera/export.hpp): hidden is
# the default for everything else, inline functions and template instances included. Static
# builds keep the compiler's default visibility, so their code is what it was before the
# package existed, and the tests, which call internal functions, link as they did.
function(tessera_set_library_properties target)
  set_target_properties(${target} PROPERTIES
    VERSION ${PROJECT_VERSION}
    SOVERSION ${PROJECT_VERSION_MAJOR})
  get_target_property(_type ${target} TYPE)
  if(_type STREQUAL "SHARED_LIBRARY")
    set_target_properties(${target} PROPERTIES
      CXX_VISIBILITY_PRESET hidden
      VISIBILITY_INLINES_HIDDEN ON)
  endif()
endfunction()
