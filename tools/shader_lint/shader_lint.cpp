// Offline shader validation: expands each shader like the renderer does and pipes it to
// glslangValidator. Usage: penumbra-shader-lint [EXTRA_NAME=FILE ...]; exits non-zero on failure.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/run_program.h"
#include "penumbra/shader_library.h"

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string stageOf(const std::string& path) {
  for (const char* stage : {"comp", "vert", "frag", "geom", "tesc", "tese"}) {
    if (endsWith(path, std::string(".") + stage)) return stage;
  }
  return "";
}

// Runs glslangValidator (no shell) on `sources` (stage, expanded text) in a private folder, all
// in one run: the validator's start (its built-in declarations for the stage) takes about 0.1 s,
// most of a variant's check, and it checks each file of a run on its own (no -l, no linking).
// Returns each source's output, empty where it passed; when the run fails, each source is run
// again alone, so a failure's log is its own.
std::vector<std::string> validate(
    const std::vector<std::pair<std::string, const penumbra::ExpandedShader*>>& sources) {
  std::vector<std::string> problems(sources.size());
  char scratch[] = "/tmp/penumbra-lint-XXXXXX";
  if (mkdtemp(scratch) == nullptr) {
    problems.assign(sources.size(), "cannot create a temporary folder");
    return problems;
  }
  const std::filesystem::path folder = scratch;
  const std::filesystem::path log = folder / "glslang.log";
  std::vector<std::string> args{"glslangValidator"};
  for (size_t i = 0; i < sources.size(); ++i) {
    // The extension names the stage.
    const std::filesystem::path input =
        folder / ("shader" + std::to_string(i) + "." + sources[i].first);
    std::ofstream(input) << sources[i].second->source;
    args.push_back(input.string());
  }
  std::string output;
  penumbra::ProgramResult result;
  try {
    result = penumbra::runProgram(args, log);
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    output = text.str();
  } catch (const penumbra::Error& e) {
    output = e.what();
  }
  std::error_code ec;
  std::filesystem::remove_all(folder, ec);
  if (result.succeeded()) return problems;
  if (!result.started) {
    problems.assign(sources.size(),
                    "glslangValidator not found: run scripts/install-deps (Debian package "
                    "glslang-tools)");
  } else if (sources.size() == 1) {
    problems[0] = sources[0].second->translateLog(output);
    // A failed run whose log is empty still failed.
    if (problems[0].empty()) problems[0] = "glslangValidator failed without a message";
  } else {
    for (size_t i = 0; i < sources.size(); ++i) problems[i] = validate({sources[i]})[0];
    // A run that failed while each of its files passes alone (killed, out of memory) still
    // failed: each of its files is reported with the run's log.
    if (std::all_of(problems.begin(), problems.end(),
                    [](const std::string& p) { return p.empty(); })) {
      problems.assign(sources.size(), "glslangValidator failed on these files together (exit " +
                                          std::to_string(result.exitCode) +
                                          ") and passed each alone:\n" + output);
    }
  }
  return problems;
}

// Every variant the renderer generates for a shader, from the variant macros its text uses:
// CHANNEL_FORMAT (each storage format and width), MSAA, SUMMED_AREA, ZMAX, REFERENCE, the
// camera pass's light kind and softness, PENUMBRA_FILTER_MODE, ALPHA_TEST, LOOKUP_INPUTS, the
// lookup's compiled-in paths, AXIS and the reduction switches (0 and 1), RADIUS and WEIGHTS (the
// blur kernels' radius and weights), TAPS_ALIKE (a box's taps summed and scaled once), LAYER_COUNT
// (the encode's fewest and most texel layers), ROWS_PER_INVOCATION (the encode's and its minimal
// copy's), and the fused tile's TILE and TEXEL_COMPONENTS (the format's).
using Defines = std::vector<penumbra::ShaderDefine>;

std::vector<Defines> variants(const std::string& source) {
  std::vector<Defines> result{{}};
  auto expand = [&](const std::string& name, std::vector<std::string> values) {
    if (source.find(name) == std::string::npos) return;
    std::vector<Defines> next;
    for (const Defines& d : result) {
      for (const std::string& v : values) {
        Defines with = d;
        with.push_back({name, v});
        next.push_back(with);
      }
    }
    result = next;
  };
  std::vector<std::string> formats;
  for (const char* components : {"r", "rg", "rgba"}) {
    for (const char* suffix : {"32f", "16f", "16", "8"})
      formats.push_back(std::string(components) + suffix);
  }
  expand("CHANNEL_FORMAT", formats);
  // The fused tile's shared arrays hold the format's components (fusedTileDefines).
  if (source.find("TEXEL_COMPONENTS") != std::string::npos) {
    for (Defines& d : result) {
      for (const penumbra::ShaderDefine& format : Defines(d)) {
        if (format.name != "CHANNEL_FORMAT") continue;
        const std::string components = format.value.rfind("rgba", 0) == 0 ? "4"
                                       : format.value.rfind("rg", 0) == 0 ? "2"
                                                                          : "1";
        d.push_back({"TEXEL_COMPONENTS", components});
      }
    }
  }
  expand("TILE", {"16"});  // the fused prefilter's work group (kFusedTile)
  // The encode's texels per invocation (encodeRowsPerInvocation).
  expand("ROWS_PER_INVOCATION", {"2", "4"});
  expand("MSAA", {"0", "1"});
  expand("SUMMED_AREA", {"0", "1"});
  expand("ZMAX", {"0", "1"});
  expand("REFERENCE", {"0", "1"});
  // The camera pass's light kinds and softness, each beside the first variant: independent
  // switches, so one variant each compiles every path (their full product would be 16x).
  if (source.find("LIGHT_PERSPECTIVE") != std::string::npos) {
    const Defines base = result.front();
    for (const Defines& kind :
         std::vector<Defines>{{{"LIGHT_PERSPECTIVE", "1"}},
                              {{"LIGHT_PERSPECTIVE", "1"}, {"POINT_LIGHT", "1"}},
                              {{"CASCADED", "1"}},
                              {{"SOFT_LIGHT", "1"}}}) {
      Defines with = base;
      with.insert(with.end(), kind.begin(), kind.end());
      result.push_back(with);
    }
  }
  expand("PENUMBRA_FILTER_MODE", {"2"});  // compiled in by lookupVariantDefines
  // Beside the first variant: a mesh pass's opaque variant (gl/material_programs.h), the camera
  // pass without the lookup's inputs (RenderSettings::lookupInputs) and without them and the
  // diagnostics (its colour alone: writesDiagnostics), and lookupParameterDefines'
  // compiled-in sizes and paths: one texel layer of channels, ESM's Z-max classifier, the paper's
  // fallback and log-space filtering (the first variant has their run-time switches).
  const std::vector<std::pair<const char*, Defines>> beside{
      {"ALPHA_TEST", {{"ALPHA_TEST", "0"}}},
      {"LOOKUP_INPUTS", {{"LOOKUP_INPUTS", "0"}}},
      {"DIAGNOSTICS", {{"LOOKUP_INPUTS", "0"}, {"DIAGNOSTICS", "0"}}},
      {"PENUMBRA_CHANNEL_CAPACITY", {{"PENUMBRA_CHANNEL_CAPACITY", "4"}}},
      {"PENUMBRA_ESM_CLASSIFIER",
       {{"PENUMBRA_ESM_CLASSIFIER", "2"},
        {"PENUMBRA_ESM_FALLBACK", "1"},
        {"PENUMBRA_ESM_FILTER_SPACE", "1"}}}};
  const Defines first = result.front();
  for (const auto& [trigger, extra] : beside) {
    if (source.find(trigger) == std::string::npos) continue;
    Defines with = first;
    with.insert(with.end(), extra.begin(), extra.end());
    result.push_back(with);
  }
  // The blur kernels' compile-time radius (blurRadiusDefine): a tap, the fused tile's largest
  // (kMaxFusedBlurRadius) and the largest of all (kMaxBlurRadius); blur.comp also compiles
  // without it (cascades: a uniform radius).
  const bool radiusOptional = source.find("#ifdef RADIUS") != std::string::npos;
  expand("RADIUS", {"0", "10", "64"});
  if (radiusOptional) {
    const std::vector<Defines> withRadius = result;
    for (const Defines& d : withRadius) {
      if (d.back().name != "RADIUS" || d.back().value != "0") continue;
      Defines without = d;
      without.pop_back();
      result.push_back(without);
    }
  }
  // WEIGHTS (blurKernelDefines) as many as the radius asks for.
  if (source.find("WEIGHTS") != std::string::npos) {
    for (Defines& d : result) {
      for (const penumbra::ShaderDefine& radius : Defines(d)) {
        if (radius.name != "RADIUS") continue;
        std::string weights = "float[](1.0";
        for (int i = 0; i < 2 * std::stoi(radius.value); ++i) weights += ", 0.0";
        d.push_back({"WEIGHTS", weights + ")"});
      }
    }
  }
  expand("AXIS", {"0", "1"});
  expand("LAYER_COUNT", {"1", "12"});  // the encode's texel layers: 1..kMaxTexelLayers
  expand("ALL_MEAN", {"0", "1"});
  expand("TAPS_ALIKE", {"0", "1"});
  expand("SOURCE_FORMAT", formats);
  expand("HALVING", {"0", "1"});
  // A pass over lib/layer_reduction.glsl resolves its reductions by one of three routes: at
  // run time (neither defined), one layer's table, or one reduction for every channel.
  if (source.find("layer_reduction.glsl") != std::string::npos) {
    std::vector<Defines> next;
    for (const Defines& d : result) {
      next.push_back(d);
      Defines table = d;
      table.push_back({"LAYER_REDUCTIONS", "ivec4(1, 2, 0, 1)"});
      next.push_back(table);
      Defines forced = d;
      forced.push_back({"FORCE_REDUCTION", "2"});
      next.push_back(forced);
    }
    result = next;
  }
  return result;
}

std::string describe(const Defines& defines) {
  std::string text;
  for (const auto& d : defines) text += " " + d.name + "=" + d.value;
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  penumbra::ShaderLibrary library;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const size_t eq = arg.find('=');
    if (eq == std::string::npos) {
      std::cerr << "usage: penumbra-shader-lint [NAME=FILE ...]\n";
      return 2;
    }
    std::ifstream in(arg.substr(eq + 1));
    if (!in) {
      std::cerr << "cannot read " << arg.substr(eq + 1) << "\n";
      return 2;
    }
    std::stringstream text;
    text << in.rdbuf();
    library.addFile(arg.substr(0, eq), text.str());
  }
  int failures = 0;
  int checked = 0;
  // Variants waiting for their run: label, stage, expanded text.
  struct Pending {
    std::string label;
    std::string stage;
    penumbra::ExpandedShader shader;
  };
  std::vector<Pending> pending;
  auto check = [&] {
    std::vector<std::pair<std::string, const penumbra::ExpandedShader*>> sources;
    for (const Pending& p : pending) sources.emplace_back(p.stage, &p.shader);
    const std::vector<std::string> problems = validate(sources);
    for (size_t i = 0; i < pending.size(); ++i) {
      ++checked;
      if (!problems[i].empty()) {
        ++failures;
        std::cerr << "FAIL " << pending[i].label << "\n" << problems[i] << "\n";
      } else {
        std::cout << "ok   " << pending[i].label << "\n";
      }
    }
    pending.clear();
  };
  // Variants per validator run: enough that its start is paid rarely, few enough that the
  // expanded texts held at once stay a few megabytes.
  constexpr size_t kVariantsPerRun = 64;
  for (const std::string& path : library.paths()) {
    std::string stage = stageOf(path);
    std::string target = path;
    if (stage.empty() && endsWith(path, ".h")) {
      // A shared header on its own: it must compile with nothing else included first.
      target = "lint/" + path + ".comp";
      library.addFile(target,
                      "#include \"" + path + "\"\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
      // Summed-area code needs 64-bit integers, enabled before any declaration.
      if (library.expand(target).source.find("SUMMED_AREA") != std::string::npos) {
        library.addFile(target,
                        "#if SUMMED_AREA\n#extension GL_ARB_gpu_shader_int64 : require\n"
                        "#endif\n#include \"" +
                            path + "\"\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
      }
      stage = "comp";
    }
    if (stage.empty()) continue;
    try {
      for (const auto& defines : variants(library.expand(target).source)) {
        pending.push_back({path + describe(defines), stage, library.expand(target, defines)});
        if (pending.size() == kVariantsPerRun) check();
      }
    } catch (const penumbra::Error& e) {
      ++failures;
      std::cerr << "FAIL " << path << ": " << e.what() << "\n";
    }
  }
  if (!pending.empty()) check();
  std::cout << checked << " shaders checked, " << failures << " failed\n";
  return failures == 0 && checked > 0 ? 0 : 1;
}
