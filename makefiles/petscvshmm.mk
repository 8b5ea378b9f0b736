# petscvshmm.mk - GNU make fragment for programs that use petsc-vshmm (TSVSHMM).
#
# Installed as <prefix>/share/petscvshmm/petscvshmm.mk; also usable from the source tree as
# makefiles/petscvshmm.mk (the library is then taken from the build directory, default
# <source>/build, or PETSCVSHMM_BUILD_DIR). A user makefile can be as small as
#
#     include /path/to/share/petscvshmm/petscvshmm.mk
#     myprog: myprog.c
#
# make's built-in rules then compile and link with the variables below. The fragment
#   - sets CC/CXX to PETSc's MPI compiler wrappers (mpicc/mpicxx) unless you set them,
#   - appends PETSCVSHMM_CFLAGS to CPPFLAGS and PETSCVSHMM_LIBS to LDLIBS
#     (define PETSCVSHMM_NO_FLAGS=1 before including it to only get the variables).
# Variables it defines:
#   PETSCVSHMM_CFLAGS   -I for petscvshmm.h and PETSc
#   PETSCVSHMM_LIBS     -lpetscvshmm and PETSc's libraries, with run paths
#   PETSCVSHMM_LIB      the path of libpetscvshmm.so (for -dll_append)
#   PETSCVSHMM_CC, PETSCVSHMM_CXX   PETSc's compilers
# PETSc is found with pkg-config (module PETSc); set PETSC_DIR [PETSC_ARCH] or
# PKG_CONFIG_PATH to choose another PETSc.

_petscvshmm_here := $(patsubst %/,%,$(dir $(abspath $(lastword $(MAKEFILE_LIST)))))

ifneq ($(wildcard $(_petscvshmm_here)/../CMakeLists.txt),)
  # source tree: <source>/makefiles/petscvshmm.mk
  PETSCVSHMM_SOURCE_DIR := $(abspath $(_petscvshmm_here)/..)
  PETSCVSHMM_BUILD_DIR ?= $(PETSCVSHMM_SOURCE_DIR)/build
  PETSCVSHMM_INCLUDE_DIR ?= $(PETSCVSHMM_SOURCE_DIR)/include
  PETSCVSHMM_LIB_DIR ?= $(abspath $(PETSCVSHMM_BUILD_DIR))/lib
else
  # installed: <prefix>/share/petscvshmm/petscvshmm.mk
  PETSCVSHMM_DIR ?= $(abspath $(_petscvshmm_here)/../..)
  PETSCVSHMM_INCLUDE_DIR ?= $(PETSCVSHMM_DIR)/include
  PETSCVSHMM_LIB_DIR ?= $(PETSCVSHMM_DIR)/lib
endif
PETSCVSHMM_LIB := $(PETSCVSHMM_LIB_DIR)/libpetscvshmm.so
ifeq ($(wildcard $(PETSCVSHMM_LIB)),)
  $(warning petscvshmm.mk: $(PETSCVSHMM_LIB) does not exist (not built or installed yet?))
endif

PKG_CONFIG ?= pkg-config
_petscvshmm_pkgconfig := $(if $(PETSC_DIR),PKG_CONFIG_PATH="$(PETSC_DIR)/$(PETSC_ARCH)/lib/pkgconfig:$(PETSC_DIR)/lib/pkgconfig:$$PKG_CONFIG_PATH") $(PKG_CONFIG)
PETSCVSHMM_PETSC_CFLAGS := $(shell $(_petscvshmm_pkgconfig) --cflags PETSc)
PETSCVSHMM_PETSC_LIBS := $(shell $(_petscvshmm_pkgconfig) --libs PETSc)
PETSCVSHMM_PETSC_LIB_DIR := $(shell $(_petscvshmm_pkgconfig) --variable=libdir PETSc)
PETSCVSHMM_CC := $(shell $(_petscvshmm_pkgconfig) --variable=ccompiler PETSc)
PETSCVSHMM_CXX := $(shell $(_petscvshmm_pkgconfig) --variable=cxxcompiler PETSc)
ifeq ($(PETSCVSHMM_PETSC_LIBS),)
  $(error petscvshmm.mk: pkg-config cannot find PETSc (module PETSc); set PETSC_DIR or PKG_CONFIG_PATH)
endif

PETSCVSHMM_CFLAGS := -I$(PETSCVSHMM_INCLUDE_DIR) $(PETSCVSHMM_PETSC_CFLAGS)
_petscvshmm_rpath := -Wl,-rpath,
PETSCVSHMM_LIBS := -L$(PETSCVSHMM_LIB_DIR) $(_petscvshmm_rpath)$(PETSCVSHMM_LIB_DIR) -lpetscvshmm \
  $(addprefix $(_petscvshmm_rpath),$(PETSCVSHMM_PETSC_LIB_DIR)) $(PETSCVSHMM_PETSC_LIBS) -lm

ifeq ($(origin CC),default)
  CC := $(or $(PETSCVSHMM_CC),mpicc)
endif
ifeq ($(origin CXX),default)
  CXX := $(or $(PETSCVSHMM_CXX),mpicxx)
endif
ifneq ($(PETSCVSHMM_NO_FLAGS),1)
  CPPFLAGS += $(PETSCVSHMM_CFLAGS)
  LDLIBS += $(PETSCVSHMM_LIBS)
endif
