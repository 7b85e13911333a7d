// Throughput of the CPU reference filters at shadow-map sizes.
#include <benchmark/benchmark.h>

#include <random>

#include "penumbra/filters.h"
#include "penumbra/summed_area_table.h"

namespace {

penumbra::Image randomImage(int size, int channels) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  penumbra::Image image(size, size, channels);
  for (float& v : image.data()) v = unit(rng);
  return image;
}

void GaussianBlur5x5(benchmark::State& state) {
  const penumbra::Image image = randomImage(int(state.range(0)), 2);
  for (auto _ : state) benchmark::DoNotOptimize(penumbra::gaussianBlur(image, 2, 1.0f));
  state.SetItemsProcessed(state.iterations() * state.range(0) * state.range(0));
}
BENCHMARK(GaussianBlur5x5)->Arg(512)->Arg(2048)->Unit(benchmark::kMillisecond);

void MipChain(benchmark::State& state) {
  const penumbra::Image image = randomImage(int(state.range(0)), 2);
  for (auto _ : state) benchmark::DoNotOptimize(penumbra::buildMipChain(image));
  state.SetItemsProcessed(state.iterations() * state.range(0) * state.range(0));
}
BENCHMARK(MipChain)->Arg(2048)->Unit(benchmark::kMillisecond);

void SummedAreaTableBuild(benchmark::State& state) {
  const penumbra::Image image = randomImage(int(state.range(0)), 2);
  for (auto _ : state) benchmark::DoNotOptimize(penumbra::SummedAreaTable(image));
  state.SetItemsProcessed(state.iterations() * state.range(0) * state.range(0));
}
BENCHMARK(SummedAreaTableBuild)->Arg(2048)->Arg(4096)->Unit(benchmark::kMillisecond);

}  // namespace
