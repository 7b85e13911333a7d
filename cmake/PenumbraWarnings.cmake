# One interface target carries the project's warning flags; every penumbra target links it.
add_library(penumbra_warnings INTERFACE)
target_compile_options(penumbra_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Woverloaded-virtual
  $<$<BOOL:${PENUMBRA_WARNINGS_AS_ERRORS}>:-Werror>
  # GCC's manual (-fsanitize=address) warns that the sanitizers raise false -Wmaybe-uninitialized
  # reports and advises against -Werror with them; GCC 12 reports std::regex's internals so. The
  # warning stays on, only not an error, in the sanitizer build.
  $<$<AND:$<BOOL:${PENUMBRA_SANITIZE}>,$<CXX_COMPILER_ID:GNU>>:-Wno-error=maybe-uninitialized>)
# The CPU reference must compute what the GPU computes: no fast-math, no contraction into FMA.
target_compile_options(penumbra_warnings INTERFACE -fno-fast-math -ffp-contract=off)
