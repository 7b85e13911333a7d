// Running the papers' performance experiments: every case rendered warm, timed, and set beside
// its experiment's baseline. The cases themselves are in paper_experiments.cpp.
#include "penumbra/compare/paper_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "penumbra/compare/comparison.h"
#include "penumbra/error.h"
#include "penumbra/metrics.h"

namespace penumbra::compare {
namespace {

gl::PassTimes medianPasses(const std::vector<gl::PassTimes>& frames) {
  auto of = [&](double gl::PassTimes::*pass) {
    std::vector<double> v;
    for (const gl::PassTimes& t : frames) v.push_back(t.*pass);
    return median(v);
  };
  gl::PassTimes m;
  m.light = of(&gl::PassTimes::light);
  m.encode = of(&gl::PassTimes::encode);
  m.prefilter = of(&gl::PassTimes::prefilter);
  m.mipsOrSat = of(&gl::PassTimes::mipsOrSat);
  m.auxiliary = of(&gl::PassTimes::auxiliary);
  m.camera = of(&gl::PassTimes::camera);
  m.depthBounds = of(&gl::PassTimes::depthBounds);
  return m;
}

const CaseMeasurement* baselineOf(const std::vector<CaseMeasurement>& all, const BenchCase& c,
                                  const std::string& series) {
  for (const CaseMeasurement& m : all) {
    if (m.benchCase.series == series && m.benchCase.x == c.x) return &m;
  }
  for (const CaseMeasurement& m : all) {  // a baseline measured once for every x
    if (m.benchCase.series == series) return &m;
  }
  return nullptr;
}

std::string format2(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  return text;
}

// Each series' cost against k: k^2 for PCF's taps, k for a separable blur, flat for a
// summed-area table. The power law is fitted with an offset over the kernels that filter
// (k >= 3): a pass's fixed cost (a blur pass that 1x1 skips, a dispatch) is the offset, where a
// fit of the cost above the 1x1 case would read it as slower growth.
std::vector<std::string> exponentFindings(const std::vector<CaseMeasurement>& cases) {
  std::vector<std::string> series;
  for (const CaseMeasurement& m : cases) {
    if (std::find(series.begin(), series.end(), m.benchCase.series) == series.end()) {
      series.push_back(m.benchCase.series);
    }
  }
  std::vector<std::string> findings;
  for (const std::string& s : series) {
    double base = 0.0, first = 0.0, last = 0.0;
    std::vector<double> k, ms;
    for (const CaseMeasurement& m : cases) {
      if (m.benchCase.series != s) continue;
      if (m.benchCase.x == 1.0) base = m.medianMs;
    }
    for (const CaseMeasurement& m : cases) {
      if (m.benchCase.series != s || m.benchCase.x <= 1.0) continue;
      if (k.empty()) first = m.medianMs;
      last = m.medianMs;
      k.push_back(m.benchCase.x);
      ms.push_back(m.medianMs);
    }
    std::string line = s + ": " + format2(first) + " ms at the smallest kernel, " + format2(last) +
                       " ms at the largest";
    if (!(last - base > 0.1 * base)) {
      line += "; flat: the largest kernel costs within a tenth of the 1x1 case";
    } else if (k.size() >= 3) {
      const PowerLawFit fit = fitPowerLaw(k, ms);
      line += "; over k >= 3 the time fits " + format2(fit.offset) + " + " + format2(fit.scale) +
              " k^" + format2(fit.exponent) + " ms";
      if (!(fit.scale > 0.0)) {
        line += " (a time that falls as the kernel grows: noise, not a cost of the kernel)";
      } else if (fit.exponent <= 0.0 || fit.exponent >= 4.0) {
        line += " (the exponent is at the edge of the searched [0, 4]: no power law fits)";
      }
    } else {
      line += "; too few filtering kernels to fit a power law";
    }
    findings.push_back(line + ".");
  }
  return findings;
}

// How the measured ratios stand against the paper's: within a quarter of them, or not, and why
// where the device explains it.
std::string paperAgreement(const std::vector<CaseMeasurement>& cases, bool softwareDevice) {
  double lowest = INFINITY, highest = 0.0;
  int compared = 0;
  for (const CaseMeasurement& m : cases) {
    if (!m.benchCase.paperTimeRatio || *m.benchCase.paperTimeRatio == 1.0) continue;
    const double quotient = m.timeRatio / *m.benchCase.paperTimeRatio;
    lowest = std::min(lowest, quotient);
    highest = std::max(highest, quotient);
    ++compared;
  }
  if (compared == 0) return "";
  const std::string range = format2(lowest) + "x to " + format2(highest) + "x the paper's";
  if (lowest >= 0.75 && highest <= 1.25) {
    return "Against the paper: agrees; our time ratios are " + range + ".";
  }
  std::string line = "Against the paper: disagrees; our time ratios are " + range + ".";
  if (softwareDevice) {
    line +=
        " This device rasterises, samples and filters in software on the CPU: every texture "
        "fetch, filter tap and transcendental costs instructions that the papers' GPUs spent in "
        "fixed-function texture units, so techniques that read more (more channels, "
        "anisotropic or trilinear filtering, wider kernels) weigh far more here. Rerun on a GPU "
        "(GPU timer queries) to compare with the papers.";
  }
  return line;
}

}  // namespace

ExperimentResult runPaperExperiment(gl::Renderer& renderer, const Scene& scene,
                                    const Experiment& experiment, int repeats) {
  if (repeats < 1 || repeats > 100) {
    throw Error("bench repeats " + std::to_string(repeats) + " is out of range [1, 100]");
  }
  for (const BenchCase& c : experiment.cases) renderer.validate(c.settings);
  const bool gpuTimers = renderer.timerQueriesMeasureExecution();
  ExperimentResult result;
  result.experiment = experiment;
  result.timing = gpuTimers ? std::string("GPU timer queries (GL_TIME_ELAPSED)")
                            : std::string("wall clock, glFinish around each pass (") +
                                  gl::kNoGpuTimesReason + ")";
  renderer.setScene(scene);
  const gl::FrameView view{scene.camera, scene.light};
  for (const BenchCase& c : experiment.cases) {
    gl::RenderSettings settings = c.settings;
    if (settings.technique == Technique::Pcf) settings.params.pcf = pcfMatchingPrefilter(settings);
    settings.readBack = gl::frame_image::kNone;  // the times and memory are all a case gives
    renderer.render(settings, view);             // warm-up: shader variants, resources
    CaseMeasurement m;
    m.benchCase = c;
    std::vector<gl::PassTimes> frames;
    for (int i = 0; i < repeats; ++i) {
      const gl::RenderResult r = renderer.render(settings, view);
      const gl::PassTimes& t = gpuTimers ? r.gpuTimes.value() : r.wallTimes.value();
      frames.push_back(t);
      m.frameMs.push_back(t.total());
      m.shadowBytes = gl::shadowMapBytes(r.memory, settings.technique);
    }
    m.medianMs = median(m.frameMs);
    m.minMs = *std::min_element(m.frameMs.begin(), m.frameMs.end());
    m.maxMs = *std::max_element(m.frameMs.begin(), m.frameMs.end());
    m.medianPasses = medianPasses(frames);
    result.cases.push_back(std::move(m));
  }
  for (CaseMeasurement& m : result.cases) {
    const CaseMeasurement* base = baselineOf(result.cases, m.benchCase, experiment.baselineSeries);
    if (base == nullptr) {
      throw Error("experiment " + experiment.id + " has no baseline case '" +
                  experiment.baselineSeries + "'");
    }
    m.timeRatio = base->medianMs > 0.0 ? m.medianMs / base->medianMs : 0.0;
    m.memoryRatio = base->shadowBytes > 0 ? double(m.shadowBytes) / double(base->shadowBytes) : 0.0;
  }
  if (experiment.fitsExponents) result.findings = exponentFindings(result.cases);
  const std::string agreement = paperAgreement(result.cases, !gpuTimers);
  if (!agreement.empty()) result.findings.push_back(agreement);
  return result;
}

PowerLawFit fitPowerLaw(const std::vector<double>& k, const std::vector<double>& ms) {
  if (k.size() != ms.size() || k.size() < 3) {
    throw Error("a fitted power law needs three or more (kernel, time) pairs");
  }
  for (size_t i = 0; i < k.size(); ++i) {
    if (!(k[i] > 0.0) || !std::isfinite(ms[i])) {
      throw Error("a fitted power law needs positive kernels and finite times");
    }
  }
  if (std::count(k.begin(), k.end(), k.front()) == std::ptrdiff_t(k.size())) {
    throw Error("a fitted power law needs two or more distinct kernels");
  }
  // For a given exponent the model is linear in (offset, scale): least squares in closed form.
  // The exponent is the grid point of [0, 4] (steps of 0.001) with the least squared error.
  PowerLawFit best;
  double bestError = INFINITY;
  const double n = double(k.size());
  for (int step = 0; step <= 4000; ++step) {
    const double p = 0.001 * double(step);
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (size_t i = 0; i < k.size(); ++i) {
      const double x = std::pow(k[i], p);
      sx += x;
      sy += ms[i];
      sxx += x * x;
      sxy += x * ms[i];
    }
    const double denominator = n * sxx - sx * sx;
    if (!(denominator > 1e-12 * n * sxx)) continue;  // p = 0: every k^p is 1
    const double scale = (n * sxy - sx * sy) / denominator;
    const double offset = (sy - scale * sx) / n;
    double error = 0.0;
    for (size_t i = 0; i < k.size(); ++i) {
      const double r = offset + scale * std::pow(k[i], p) - ms[i];
      error += r * r;
    }
    if (error < bestError) {
      bestError = error;
      best = {offset, scale, p};
    }
  }
  return best;
}

}  // namespace penumbra::compare
