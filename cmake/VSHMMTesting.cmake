# Test helpers for petsc-vshmm: MPI launcher settings and vshmm_example_test().

# mpiexec plus the flags OpenMPI needs when the tests run as root (containers, CI) or on more
# ranks than cores. Override with -DVSHMM_MPIEXEC_PREFLAGS="..." if needed.
if(NOT DEFINED VSHMM_MPIEXEC_PREFLAGS)
  set(_flags ${MPIEXEC_PREFLAGS})
  execute_process(COMMAND ${MPIEXEC_EXECUTABLE} --version OUTPUT_VARIABLE _mpiexec_version
                  ERROR_QUIET RESULT_VARIABLE _rc)
  if(_mpiexec_version MATCHES "Open MPI|OpenRTE")
    execute_process(COMMAND id -u OUTPUT_VARIABLE _uid OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(_uid STREQUAL "0")
      list(APPEND _flags --allow-run-as-root)
    endif()
    list(APPEND _flags --oversubscribe)
  endif()
  set(VSHMM_MPIEXEC_PREFLAGS "${_flags}" CACHE STRING "Flags given to mpiexec before the program")
endif()

set(VSHMM_NUMDIFF ${PROJECT_SOURCE_DIR}/tests/numdiff.sh)
set(VSHMM_RUN_TEST_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/VSHMMRunTest.cmake)

# vshmm_mpiexec_command(<out-var> <np>): the list "mpiexec -n <np> <flags>" for add_test().
function(vshmm_mpiexec_command out np)
  set(${out} ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${np} ${VSHMM_MPIEXEC_PREFLAGS} PARENT_SCOPE)
endfunction()

#[[
vshmm_example_test(NAME <test> EXE <target> [NP <n>] [ARGS <arg>...]
                   [OUTPUT <expected file>] [RTOL <r>] [ATOL <a>] [REGEX <regex>]
                   [STDERR_REGEX <regex>] [STDERR_NOT_REGEX <regex>]
                   [VALUE_REGEX <regex> VALUE_MAX <x>] [EXPECT_FAILURE]
                   [FILE <file> FILE_REGEX <regex>]
                   [ENVIRONMENT <VAR=value>...] [LABELS <label>...]   (default: example)
                   [TIMEOUT <seconds>])                               (default: 300)

Runs `mpiexec -n <n> <flags> <target's file> <args>` (NP defaults to 1) in
<build>/tests/output/<test>/ and passes when the program exits with 0 (with EXPECT_FAILURE:
with any other status) and
  - REGEX (if given) matches its standard output, STDERR_REGEX (if given) its standard error,
    and STDERR_NOT_REGEX (if given) does not match its standard error (a warning that must not
    be given),
  - the first group of VALUE_REGEX (if given) in its standard output is a number <= VALUE_MAX,
  - the file FILE (if given; relative to the working directory, removed before the run) exists
    and matches FILE_REGEX, and
  - OUTPUT (if given; relative paths are relative to the directory of the file that calls
    this function) matches its standard output according to tests/numdiff.sh: tokens compared
    one by one, numbers within relative tolerance RTOL (default 1e-6) or absolute tolerance
    ATOL (default 1e-10).
The standard output is kept in <build>/tests/output/<test>/stdout.txt; to (re)generate an
expected file, copy it from there after checking it. EXE may also be a path to a program.
#]]
function(vshmm_example_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "EXPECT_FAILURE" "NAME;EXE;NP;OUTPUT;RTOL;ATOL;REGEX;STDERR_REGEX;STDERR_NOT_REGEX;VALUE_REGEX;VALUE_MAX;FILE;FILE_REGEX;TIMEOUT" "ARGS;ENVIRONMENT;LABELS")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "vshmm_example_test: unknown arguments ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT arg_NAME OR NOT arg_EXE)
    message(FATAL_ERROR "vshmm_example_test: NAME and EXE are required")
  endif()
  if(NOT arg_NP)
    set(arg_NP 1)
  endif()
  if(TARGET ${arg_EXE})
    set(exe $<TARGET_FILE:${arg_EXE}>)
  else()
    set(exe ${arg_EXE})
  endif()
  set(defs -DNAME=${arg_NAME} -DNUMDIFF=${VSHMM_NUMDIFF})
  if(DEFINED arg_OUTPUT)
    get_filename_component(expected "${arg_OUTPUT}" ABSOLUTE BASE_DIR ${CMAKE_CURRENT_LIST_DIR})
    if(NOT EXISTS "${expected}")
      message(WARNING "vshmm_example_test(${arg_NAME}): expected output ${expected} does not exist")
    endif()
    list(APPEND defs "-DOUTPUT=${expected}")
  endif()
  foreach(opt RTOL ATOL)
    if(DEFINED arg_${opt})
      list(APPEND defs "-D${opt}=${arg_${opt}}")
    endif()
  endforeach()
  if(DEFINED arg_FILE)
    if(NOT DEFINED arg_FILE_REGEX)
      message(FATAL_ERROR "vshmm_example_test(${arg_NAME}): FILE needs FILE_REGEX")
    endif()
    list(APPEND defs "-DFILE=${arg_FILE}")
  endif()
  foreach(opt REGEX STDERR_REGEX STDERR_NOT_REGEX VALUE_REGEX FILE_REGEX)
    if(DEFINED arg_${opt})
      string(REPLACE ";" "\\;" regex "${arg_${opt}}")
      list(APPEND defs "-D${opt}=${regex}")
    endif()
  endforeach()
  if(DEFINED arg_VALUE_REGEX)
    if(NOT DEFINED arg_VALUE_MAX)
      message(FATAL_ERROR "vshmm_example_test(${arg_NAME}): VALUE_REGEX needs VALUE_MAX")
    endif()
    list(APPEND defs "-DVALUE_MAX=${arg_VALUE_MAX}")
  endif()
  if(arg_EXPECT_FAILURE)
    list(APPEND defs -DEXPECT_FAILURE=1)
  endif()
  set(workdir ${PROJECT_BINARY_DIR}/tests/output/${arg_NAME})
  file(MAKE_DIRECTORY ${workdir})
  vshmm_mpiexec_command(launcher ${arg_NP})
  add_test(NAME ${arg_NAME}
           COMMAND ${CMAKE_COMMAND} ${defs} -P ${VSHMM_RUN_TEST_SCRIPT} -- ${launcher} ${exe} ${arg_ARGS}
           WORKING_DIRECTORY ${workdir})
  if(NOT arg_LABELS)
    set(arg_LABELS example)
  endif()
  if(NOT arg_TIMEOUT)
    set(arg_TIMEOUT 300)
  endif()
  set_tests_properties(${arg_NAME} PROPERTIES PROCESSORS ${arg_NP} LABELS "${arg_LABELS}" TIMEOUT ${arg_TIMEOUT})
  if(arg_ENVIRONMENT)
    set_tests_properties(${arg_NAME} PROPERTIES ENVIRONMENT "${arg_ENVIRONMENT}")
  endif()
endfunction()
