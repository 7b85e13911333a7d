// Each prefilter pass beside a minimal kernel with the same reads and writes, timed side by side
// in one run (`penumbra bench --passes`): how close the passes come to what the device can do.
#pragma once

#include <string>
#include <vector>

#include "penumbra/gl/renderer.h"

namespace penumbra::gl {

// The times of a pass and its kernels over the warm frames: the fastest frame's, which the ratios
// use, and the median. On a 2-core machine llvmpipe's two rasteriser threads sometimes share one
// core for a whole pass, which doubles its time (one thread, LP_NUM_THREADS=1, gives the slow
// mode on every frame); the fastest frame is the pass with the device to itself, as a GPU's pass
// is, and the median mixes the modes in a proportion that differs between the two sides.
struct FrameTimes {
  double fastestMs = 0.0;
  double medianMs = 0.0;
  int samples = 0;  // the times they are of
};

// The camera pass's draws a frame, each followed by its minimal lookups: its first draw is the
// frame's own, the others Renderer::timeCameraPass. A camera pass takes a few milliseconds where a
// frame takes tens, so that one draw a frame left the pass and its yardstick a sample or two
// outside llvmpipe's slow phases (both rasteriser threads on one core) and a ratio up to 1.47x
// where the next run read 1.18x (docs/results/passes-llvmpipe-2026-12-06-night.md).
constexpr int kCameraDrawsPerFrame = 4;
// The encode pass's dispatches a frame, each timed beside a run of its minimal copy (the
// yardstick's copy, informative, stays at one a frame): its first is the frame's own, the others
// Renderer::timeEncodePass. With one a frame the fastest of 15 frames moved CSM's encode against
// its copy 1.19-1.46x from run to run, the fastest of 60 frames 1.22-1.29x
// (docs/results/passes-llvmpipe-2026-12-07/csm-encode-experiments.txt, N).
constexpr int kEncodeDispatchesPerFrame = 4;

// The fastest and the median of a pass's frame times; zeros for none.
FrameTimes frameTimes(const std::vector<double>& times);

struct PassTiming {
  // "encode", "prefilter", "encode + prefilter, fused", "mips", "camera", ... (ESM with a
  // classifier: also "camera, classification off")
  std::string pass;
  FrameTimes passTimes;  // the renderer's pass
  std::string baseline;  // what the minimal kernel does
  FrameTimes baselineTimes;
  // The independent yardstick (../shared/yardsticks/rawblur.c's copy and blur, run here on a 2D
  // texture of as many 32-bit float components per texel as the channel texture has, once per
  // layer: for 8- and 16-bit channels it moves 2-4x their bytes), beside the encode, the blur
  // and the fused pass: empty and 0 for the mips and the summed-area table.
  std::string yardstick;
  FrameTimes yardstickTimes;
  double passMs() const { return passTimes.fastestMs; }
  double baselineMs() const { return baselineTimes.fastestMs; }
  double yardstickMs() const { return yardstickTimes.fastestMs; }
  double ratio() const { return baselineMs() > 0.0 ? passMs() / baselineMs() : 0.0; }
  // The minimal kernel against the yardstick: at most about 1 when the minimal kernel is minimal.
  double baselineToYardstick() const {
    return yardstickMs() > 0.0 ? baselineMs() / yardstickMs() : 0.0;
  }
};

struct PassBenchResult {
  Technique technique = Technique::Vsm;
  std::string format;  // the channel texture's format, e.g. "rgba32f x 1 layer"
  std::string timing;  // "GPU timer queries" or "wall clock (...)"
  std::vector<PassTiming> passes;
};

// How bench --passes times on this renderer's device: "GPU timer queries" where they measure
// execution, else "wall clock (glFinish around each pass)" (PassBenchResult::timing).
std::string passTimingDescription(const Renderer& renderer);
// Which rows take more than one sample a frame, for bench's texts: "the camera pass drawn 4 times
// a frame, each draw before its minimal lookup, and the separate encode dispatched 4 times, each
// timed beside a run of its copy".
std::string passSamplingDescription();

// Renders `scene` with `settings` (1 warm-up frame, then `repeats` frames) with the separate
// passes and, where the settings allow it, with the fused prefilter, and runs the minimal kernels
// as many times on textures of the channel texture's format, size and layers (FrameTimes: the
// fastest frame and the median) of GPU timer queries on vendor drivers, of wall-clock times on
// software rasterisers (llvmpipe's queries see only submission). The mip chain or, with the sat
// filter, the summed-area table. The camera pass stands beside the least lookup of the technique;
// ESM's with the threshold classifier beside a lookup that classifies and falls back as the pass
// does (the ESM paper's classification, §3.3, with the pass's fallback). ESM's with a classifier
// also, after the fused frames, in frames of its own with the classification off beside the least
// lookup ("camera, classification off"); the bench ends on those frames, whose draws the pass's
// and the yardstick's targets then hold. The Z-max classifier reads a pyramid the yardstick does
// not build: its "camera" row stands beside the least lookup, which says so. PCF and the hard test
// have no prefilter, cascades and point lights have several maps, and soft lights a blocker
// search the minimal lookup lacks: they are refused.
PassBenchResult benchPasses(Renderer& renderer, const Scene& scene, const RenderSettings& settings,
                            int repeats);

// Throws Error with the reason where bench --passes cannot measure `settings` on `scene`: the
// minimal kernels run on one map (no cascades, no point light's six faces), and the minimal
// lookup has no blocker search to stand beside a soft light's. benchPasses checks it too; a
// front end calls it before it creates a GL context or its output.
void checkPassBenchable(const Scene& scene, const RenderSettings& settings);

}  // namespace penumbra::gl
