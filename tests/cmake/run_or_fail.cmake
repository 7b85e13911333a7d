# run(COMMAND...): runs a command as an argument vector (no shell) and stops the script with its
# output when it fails. For the scripts that install the build and build a consumer against it.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
endfunction()
