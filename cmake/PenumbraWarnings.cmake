# One interface target carries the project's warning flags; every penumbra target links it.
add_library(penumbra_warnings INTERFACE)
target_compile_options(penumbra_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Woverloaded-virtual
  $<$<BOOL:${PENUMBRA_WARNINGS_AS_ERRORS}>:-Werror>)
# The CPU reference must compute what the GPU computes: no fast-math, no contraction into FMA.
target_compile_options(penumbra_warnings INTERFACE -fno-fast-math -ffp-contract=off)
