// The scene memory budget the fuzz targets load with: a quarter of the 2048 MiB that
// scripts/fuzz-loaders gives libFuzzer (-rss_limit_mb, -malloc_limit_mb), leaving room for the
// sanitizers' own memory and the transient copies the budget does not count (an image while it
// is decoded, the parsers' JSON and OBJ structures). Anything the budget lets through that still
// reaches the limit is an unbounded allocation: a fuzz failure.
#pragma once

#include <cstdint>

namespace penumbra::fuzz {

inline constexpr uint64_t kMemoryBudgetBytes = uint64_t(512) << 20;

}  // namespace penumbra::fuzz
