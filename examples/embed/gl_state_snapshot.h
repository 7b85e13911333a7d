// The host's own record of the GL state a guest could disturb: bindings, enables, fixed-function
// settings, the debug callback and the sampling parameters of the host's textures. Two
// snapshots around a call to penumbra show whether it left the context as it found it.
#pragma once

#include <map>
#include <span>
#include <string>

using GlStateSnapshot = std::map<std::string, std::string>;  // what -> its value as text

// Needs a current GL 4.5 context. Restores the active texture unit it walks through.
// `hostTextures`: textures whose parameters (filters, compare mode, levels, swizzle) count too.
GlStateSnapshot takeGlStateSnapshot(std::span<const unsigned> hostTextures);

// One line per entry that differs ("what: before -> after"); empty when they are equal.
std::string describeDifferences(const GlStateSnapshot& before, const GlStateSnapshot& after);
