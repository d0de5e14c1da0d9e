# Warning and sanitizer flags for the project's own targets (never forced on users).
add_library(flexstress_dev_flags INTERFACE)
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  target_compile_options(flexstress_dev_flags INTERFACE -Wall -Wextra -Wpedantic)
  if(FLEXSTRESS_WARNINGS_AS_ERRORS)
    target_compile_options(flexstress_dev_flags INTERFACE -Werror)
  endif()
  if(FLEXSTRESS_SANITIZE)
    target_compile_options(flexstress_dev_flags INTERFACE
      -fsanitize=${FLEXSTRESS_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all)
    target_link_options(flexstress_dev_flags INTERFACE -fsanitize=${FLEXSTRESS_SANITIZE})
  endif()
endif()
