# mpi_launcher(VAR): MPIEXEC with what Open MPI needs here: more ranks than cores (--oversubscribe), and the CI's root
# (--allow-run-as-root). Included by the ctest -P scripts that run mpirun (mpi_runs.cmake, plugin_example.cmake).
function(mpi_launcher var)
  set(launcher ${MPIEXEC})
  execute_process(COMMAND ${MPIEXEC} --version OUTPUT_VARIABLE version ERROR_QUIET)
  if(version MATCHES "Open MPI|OpenRTE")
    list(APPEND launcher --oversubscribe)
    execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(uid STREQUAL "0")
      list(APPEND launcher --allow-run-as-root)
    endif()
  endif()
  set(${var} ${launcher} PARENT_SCOPE)
endfunction()
