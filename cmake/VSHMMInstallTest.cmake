# Test script: install the build tree BUILD_DIR into a fresh PREFIX and check the layout.
#   cmake -DBUILD_DIR=<build> -DPREFIX=<prefix> -DVERSION=x.y.z -DSOVERSION=x.y [-DSPECTRAL=ON]
#         -P VSHMMInstallTest.cmake
# SPECTRAL: the build has the spectral component (libpetscvshmmspectral); without it, none of
# its files may be installed.
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX} RESULT_VARIABLE rc)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "cmake --install ${BUILD_DIR} --prefix ${PREFIX} failed")
endif()

set(missing)
foreach(f
    include/petscvshmm.h
    lib/libpetscvshmm.so
    lib/libpetscvshmm.so.${SOVERSION}
    lib/libpetscvshmm.so.${VERSION}
    lib/pkgconfig/petscvshmm.pc
    lib/cmake/PetscVSHMM/PetscVSHMMConfig.cmake
    lib/cmake/PetscVSHMM/PetscVSHMMConfigVersion.cmake
    lib/cmake/PetscVSHMM/PetscVSHMMTargets.cmake
    share/petscvshmm/petscvshmm.mk)
  if(NOT EXISTS ${PREFIX}/${f})
    list(APPEND missing ${f})
  endif()
endforeach()
set(spectral_files
    include/petscvshmmspectral.h
    lib/libpetscvshmmspectral.so
    lib/libpetscvshmmspectral.so.${SOVERSION}
    lib/pkgconfig/petscvshmmspectral.pc
    lib/cmake/PetscVSHMM/PetscVSHMMSpectralTargets.cmake)
set(unexpected)
foreach(f IN LISTS spectral_files)
  if(SPECTRAL AND NOT EXISTS ${PREFIX}/${f})
    list(APPEND missing ${f})
  elseif(NOT SPECTRAL AND EXISTS ${PREFIX}/${f})
    list(APPEND unexpected ${f})
  endif()
endforeach()
if(missing)
  message(FATAL_ERROR "missing in ${PREFIX}: ${missing}")
endif()
if(unexpected)
  message(FATAL_ERROR "installed in ${PREFIX} by a build without the spectral component: ${unexpected}")
endif()

# The TS library does not need FFTW.
find_program(READELF readelf)
if(READELF)
  execute_process(COMMAND ${READELF} -d ${PREFIX}/lib/libpetscvshmm.so OUTPUT_VARIABLE dyn)
  if(dyn MATCHES "libfftw3")
    message(FATAL_ERROR "libpetscvshmm.so needs FFTW (readelf -d): only the spectral component may")
  endif()
endif()

# The shared library must export the PETSc dynamic-library entry point (-dll_append) and the API.
find_program(NM nm)
if(NM)
  execute_process(COMMAND ${NM} -D --defined-only ${PREFIX}/lib/libpetscvshmm.so OUTPUT_VARIABLE syms)
  foreach(s PetscDLLibraryRegister_petscvshmm TSVSHMMInitializePackage)
    if(NOT syms MATCHES "[ \t]T ${s}\n")
      message(FATAL_ERROR "libpetscvshmm.so does not export ${s}")
    endif()
  endforeach()
endif()

file(GLOB_RECURSE installed RELATIVE ${PREFIX} LIST_DIRECTORIES false ${PREFIX}/*)
list(SORT installed)
string(REPLACE ";" "\n  " installed "${installed}")
message("installed in ${PREFIX}:\n  ${installed}")
