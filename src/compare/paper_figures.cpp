// `penumbra figures`: the page that gathers every regenerated figure and table.
#include "penumbra/compare/paper_figures.h"

#include <fstream>

#include "penumbra/compare/html_text.h"
#include "penumbra/compare/paper_bench_report.h"
#include "penumbra/error.h"
#include "penumbra/text_file.h"

namespace penumbra::compare {
namespace {

std::string itemHtml(const FigureItem& f) {
  std::string h = "<section id=\"" + f.id + "\"><h2>" + escapeHtml(f.title) + "</h2>\n";
  for (const std::string& image : f.images) {
    h += "<img src=\"" + image + "\" alt=\"" + escapeHtml(f.title) + "\">\n";
  }
  h += f.tableHtml + "\n<p><b>Paper:</b> " + escapeHtml(f.paper) + "</p>\n<p><b>Measured:</b> " +
       escapeHtml(f.measured) + "</p>\n<p class=\"" + (f.agrees ? "agree" : "disagree") + "\"><b>" +
       (f.agrees ? "Agrees" : "Disagrees") + ":</b> " + escapeHtml(f.verdict) + "</p></section>\n";
  return h;
}

std::string benchHtml(const std::vector<ExperimentResult>& results) {
  std::string h;
  for (const ExperimentResult& r : results) {
    const Experiment& e = r.experiment;
    const gl::RenderSettings& first = e.cases.front().settings;
    h += "<section id=\"" + e.id + "\"><h2>" + escapeHtml(e.title) + "</h2>\n<p><b>Paper:</b> " +
         escapeHtml(e.claim) + "</p>\n<p>Ours at " + std::to_string(first.shadowMapSize) + "² (" +
         std::to_string(first.width) + "x" + std::to_string(first.height) +
         " frame; the bench command takes the papers' "
         "2048²).</p>\n<table><tr><th>case</th><th>time / " +
         escapeHtml(e.baselineSeries) + "</th><th>paper</th><th>memory / " +
         escapeHtml(e.baselineSeries) + "</th><th>paper</th></tr>";
    for (const CaseMeasurement& m : r.cases) {
      auto cell = [](const std::optional<double>& v) {
        if (!v) return std::string("not given");
        char text[32];
        std::snprintf(text, sizeof text, "%.2f", *v);
        return std::string(text);
      };
      char ours[64];
      std::snprintf(ours, sizeof ours, "%.2f</td><td>", m.timeRatio);
      char memory[32];
      std::snprintf(memory, sizeof memory, "%.2f", m.memoryRatio);
      h += "<tr><td>" + escapeHtml(m.benchCase.label) + "</td><td>" + ours +
           cell(m.benchCase.paperTimeRatio) + "</td><td>" + memory + "</td><td>" +
           cell(m.benchCase.paperMemoryRatio) + "</td></tr>";
    }
    h += "</table>\n";
    if (!e.xLabel.empty()) h += "<img src=\"bench/plots/" + e.id + ".png\" alt=\"" + e.id + "\">\n";
    for (const std::string& f : r.findings) h += "<p>" + escapeHtml(f) + "</p>\n";
    h += "<p><b>Measured:</b> " + escapeHtml(r.timing) +
         "; details in <a href=\"bench/index.html#" + e.id +
         "\">the bench page</a>.</p></section>\n";
  }
  return h;
}

}  // namespace

void writePaperFigures(gl::Renderer& renderer, const FiguresOptions& options,
                       const std::filesystem::path& dir, const FiguresProgress& progress) {
  auto step = [&](const std::string& what) {
    if (progress) progress(what);
  };
  step("step-function curves");
  std::vector<FigureItem> items = curveFigures(dir);
  for (FigureItem& f : renderedFigures(renderer, options, dir, progress)) items.push_back(f);

  const Scene scene = makeBuiltinScene("backyard");
  std::vector<ExperimentResult> bench;
  for (const std::string& id : paperExperimentIds()) {
    step("bench: " + id);
    bench.push_back(runPaperExperiment(renderer, scene, makePaperExperiment(id, options.benchSizes),
                                       options.benchRepeats));
  }
  writePaperBenchReport(
      bench, {renderer.deviceDescription(), scene.name, options.benchRepeats, options.command},
      dir / "bench");

  int disagreements = 0;
  for (const FigureItem& f : items) disagreements += f.agrees ? 0 : 1;
  std::string page =
      "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>penumbra figures: "
      "the seed papers regenerated</title>\n<style>body{font-family:sans-serif;max-width:1200px;"
      "margin:2em auto;padding:0 "
      "1em}img{max-width:48%;margin:4px;vertical-align:top}table{border-collapse:"
      "collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:3px 8px}.agree{color:#1b5e20}"
      ".disagree{color:#b71c1c}section{border-top:1px solid #ddd;margin-top:2em}</style></head>"
      "<body>\n<h1>The seed papers' figures and tables, regenerated with "
      "penumbra</h1>\n<p>Device: " +
      escapeHtml(renderer.deviceDescription()) + ". Command: <code>" + escapeHtml(options.command) +
      "</code>. " + std::to_string(items.size()) + " figures, " + std::to_string(disagreements) +
      " disagreeing with their paper (each says why), and the papers' performance tables.</p>\n";
  page += "<ul>";
  for (const FigureItem& f : items)
    page += "<li><a href=\"#" + f.id + "\">" + escapeHtml(f.title) + "</a></li>";
  for (const ExperimentResult& r : bench) {
    page +=
        "<li><a href=\"#" + r.experiment.id + "\">" + escapeHtml(r.experiment.title) + "</a></li>";
  }
  page += "</ul>\n";
  for (const FigureItem& f : items) page += itemHtml(f);
  page += benchHtml(bench) + "</body></html>\n";
  writeTextFile(dir / "index.html", page);
}

}  // namespace penumbra::compare
