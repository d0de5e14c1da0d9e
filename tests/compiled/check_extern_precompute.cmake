# A user's unit that builds an FE model and reduces it, compiled against flexstress::compiled,
# calls the precompute without compiling it (the headers declare it extern under
# FLEXSTRESS_COMPILED, core/precompute.hpp): its object file references reduction::reduce<void>
# and fe::assemble<void> and defines neither. Compiled there, they took a one-file user program
# 98 to 117 s and 2.7 GB with GCC -O2 instead of 12 s and 0.8 GB (docs/performance.md).
#   cmake -DNM=<nm> -DOBJECTS=<object files> -P check_extern_precompute.cmake
execute_process(COMMAND "${NM}" -C ${OBJECTS} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} failed (${rc}): ${err}")
endif()
foreach(entry "flexstress::reduction::reduce<void>" "flexstress::fe::assemble<void>")
  if(out MATCHES "\n[0-9a-f]+ [TtWw] [^\n]*${entry}\\(")
    message(FATAL_ERROR "the unit compiles ${entry} itself instead of using flexstress::compiled")
  endif()
  if(NOT out MATCHES "\n +U [^\n]*${entry}\\(")
    message(FATAL_ERROR "the unit does not reference ${entry}: the check checks nothing")
  endif()
endforeach()
message(STATUS "the precompute is referenced, not compiled")
