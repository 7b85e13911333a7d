// --check-state: whether a call into penumbra leaves the host's GL context as it found it.
#pragma once

#include <functional>

// The host's objects the check binds everywhere before the call (so that a guest that resets
// state to defaults, instead of restoring it, shows).
struct HostObjects {
  unsigned program, vertexArray, framebuffer, depthTexture, buffer;
};

// Sets unusual state, snapshots it, leaves a host GL error pending, runs `call`, and compares:
// the snapshot (the host's debug callback among it), the pending error (still the host's only)
// and, in a debug context, the errors reported to the host's callback (the host's only). Prints
// the differences to stderr; true when there are none. The state stays as the check set it.
bool callKeepsHostState(const HostObjects& host, const std::function<void()>& call);
