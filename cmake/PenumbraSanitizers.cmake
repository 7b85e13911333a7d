# PENUMBRA_SANITIZE: AddressSanitizer and UndefinedBehaviorSanitizer on every target (flags set
# globally so that the tests and the package-consumer test, which gets them passed on, match).
# Undefined behaviour is fatal; leaks stay detected, Mesa's own are suppressed at test time by
# cmake/lsan_suppressions.txt (the asan test preset).
set(PENUMBRA_SANITIZER_FLAGS "")
if(PENUMBRA_SANITIZE)
  set(PENUMBRA_SANITIZER_FLAGS
      "-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer")
  string(APPEND CMAKE_CXX_FLAGS " ${PENUMBRA_SANITIZER_FLAGS}")
  string(APPEND CMAKE_EXE_LINKER_FLAGS " ${PENUMBRA_SANITIZER_FLAGS}")
  string(APPEND CMAKE_SHARED_LINKER_FLAGS " ${PENUMBRA_SANITIZER_FLAGS}")
endif()
