# Script: install BUILD_DIR into SCRATCH/prefix, configure and build CONSUMER against it, run it.
file(REMOVE_RECURSE ${SCRATCH})
include(${CMAKE_CURRENT_LIST_DIR}/../cmake/run_or_fail.cmake)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${SCRATCH}/prefix)
# The consumer builds with the flags penumbra was built with (the sanitizers', if any).
run(${CMAKE_COMMAND} -S ${CONSUMER} -B ${SCRATCH}/build -G Ninja -DCMAKE_PREFIX_PATH=${SCRATCH}/prefix
    "-DCMAKE_CXX_FLAGS=${CONSUMER_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_FLAGS}")
run(${CMAKE_COMMAND} --build ${SCRATCH}/build)
# The CPU twin rounds like the GPU only without fused multiply-adds: a usage requirement, so the
# consumer's own compile lines must carry it.
file(READ ${SCRATCH}/build/build.ninja consumer_build)
if(NOT consumer_build MATCHES "-ffp-contract=off")
  message(FATAL_ERROR "the consumer was compiled without -ffp-contract=off (penumbra::core's "
                      "usage requirement)")
endif()
run(${SCRATCH}/build/consumer)
# The GL consumer, whenever penumbra was built with its GL library.
if(WITH_GL)
  if(NOT EXISTS ${SCRATCH}/build/gl_consumer)
    message(FATAL_ERROR "penumbra was built with penumbra::gl, but the package did not give it")
  endif()
  run(${SCRATCH}/build/gl_consumer)
endif()
