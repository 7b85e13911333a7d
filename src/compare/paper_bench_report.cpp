// `penumbra bench`'s outputs: bench.json, bench.csv and index.html with one gnuplot plot per
// swept experiment, each case's ratio beside the paper's.
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "penumbra/compare/html_text.h"
#include "penumbra/compare/paper_bench_report.h"
#include "penumbra/csv_field.h"
#include "penumbra/error.h"
#include "penumbra/output_journal.h"
#include "penumbra/gl/render_record.h"
#include "penumbra/gnuplot.h"
#include "penumbra/text_file.h"

namespace penumbra::compare {
namespace {

using nlohmann::ordered_json;

// Median time against x, one line per series, log-log when the sweep spans a decade.
void plotSweep(const ExperimentResult& r, const std::filesystem::path& png) {
  std::map<std::string, std::vector<const CaseMeasurement*>> bySeries;
  std::vector<std::string> order;
  for (const CaseMeasurement& m : r.cases) {
    if (bySeries[m.benchCase.series].empty()) order.push_back(m.benchCase.series);
    bySeries[m.benchCase.series].push_back(&m);
  }
  GnuplotRun gnuplot(png.parent_path());
  const std::filesystem::path data = gnuplot.scratchFile("sweep.dat");
  {
    std::ofstream out(data);
    for (const std::string& s : order) {
      for (const CaseMeasurement* m : bySeries[s]) {
        out << m->benchCase.x << " " << m->medianMs << " " << m->minMs << " " << m->maxMs << "\n";
      }
      out << "\n\n";
    }
    if (!out) throw Error("cannot write " + data.string());
  }
  const bool logScale = r.experiment.id == "kernel-scaling";
  std::ostringstream gp;
  gp << "set terminal pngcairo size 720,460 font 'DejaVu Sans,10'\n"
     << "set output " << gnuplotOutput(png) << "\n"
     << "set title " << gnuplotText(r.experiment.title) << " noenhanced\n"
     << "set xlabel " << gnuplotText(r.experiment.xLabel) << " noenhanced\n"
     << "set ylabel 'frame shadow cost, ms (median; bars: min-max)'\nset grid\n"
     << "set key top left noenhanced\n"
     << (logScale ? "set logscale xy\n" : "set yrange [0:*]\n") << "plot ";
  for (size_t i = 0; i < order.size(); ++i) {
    gp << (i ? ", " : "") << gnuplotPath(data) << " index " << i
       << " using 1:2:3:4 with yerrorlines lw 2 title " << gnuplotText(order[i]);
  }
  gp << "\n";
  gnuplot.run(gp.str());
}

ordered_json caseJson(const CaseMeasurement& m) {
  ordered_json j = {{"label", m.benchCase.label},
                    {"series", m.benchCase.series},
                    {"x", m.benchCase.x},
                    {"technique", techniqueId(m.benchCase.settings.technique)},
                    {"shadow_map_size", m.benchCase.settings.shadowMapSize},
                    {"median_ms", m.medianMs},
                    {"min_ms", m.minMs},
                    {"max_ms", m.maxMs},
                    {"frames_ms", m.frameMs},
                    {"passes_median_ms", ordered_json::parse(gl::passTimesJson(m.medianPasses))},
                    {"shadow_bytes", m.shadowBytes},
                    {"time_ratio", m.timeRatio},
                    {"memory_ratio", m.memoryRatio}};
  if (m.benchCase.paperTimeRatio) j["paper_time_ratio"] = *m.benchCase.paperTimeRatio;
  if (m.benchCase.paperMemoryRatio) j["paper_memory_ratio"] = *m.benchCase.paperMemoryRatio;
  if (!m.benchCase.paperNote.empty()) j["paper_note"] = m.benchCase.paperNote;
  return j;
}

}  // namespace

void writePaperBenchReport(const std::vector<ExperimentResult>& results,
                           const PaperBenchContext& context, const std::filesystem::path& dir) {
  createOutputDirectory(dir / "plots");
  ordered_json experiments = ordered_json::array();
  std::ostringstream csv;
  csv << "experiment,label,series,x,median_ms,min_ms,max_ms,shadow_bytes,time_ratio,"
         "memory_ratio,paper_time_ratio,paper_memory_ratio\n";
  std::ostringstream page;
  page << "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
       << "<title>penumbra bench: the papers' performance experiments</title>\n"
       << "<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em}"
       << "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:3px 8px;"
       << "text-align:right}td:first-child,th:first-child{text-align:left}"
       << ".note{color:#555;font-size:90%}</style></head><body>\n"
       << "<h1>The papers' performance experiments, rerun</h1>\n"
       << "<p>Device: " << escapeHtml(context.device)
       << ". Timing: " << escapeHtml(results.empty() ? "" : results[0].timing) << ". Scene <code>"
       << escapeHtml(context.scene) << "</code>; one warm-up frame, then " << context.repeats
       << " timed frames per case (median, min-max). Command: <code>" << escapeHtml(context.command)
       << "</code>.</p>\n"
       << "<p>The papers' times come from their GPUs (GeForce 8800 GTX, GTX 280); what can be "
          "compared is each "
          "ratio against the experiment's baseline, and how cost grows.</p>\n";
  for (const ExperimentResult& r : results) {
    const Experiment& e = r.experiment;
    const gl::RenderSettings& first = e.cases.front().settings;
    const std::string sizes = "Measured at " + std::to_string(first.shadowMapSize) + "² (" +
                              std::to_string(first.width) + "x" + std::to_string(first.height) +
                              " frame).";
    ordered_json cases = ordered_json::array();
    for (const CaseMeasurement& m : r.cases) {
      cases.push_back(caseJson(m));
      csv << e.id << "," << csvField(m.benchCase.label) << "," << csvField(m.benchCase.series)
          << "," << m.benchCase.x << "," << m.medianMs << "," << m.minMs << "," << m.maxMs << ","
          << m.shadowBytes << "," << m.timeRatio << "," << m.memoryRatio << ","
          << (m.benchCase.paperTimeRatio ? fixedDigits(*m.benchCase.paperTimeRatio, 3) : "") << ","
          << (m.benchCase.paperMemoryRatio ? fixedDigits(*m.benchCase.paperMemoryRatio, 3) : "")
          << "\n";
    }
    experiments.push_back({{"id", e.id},
                           {"title", e.title},
                           {"claim", e.claim},
                           {"baseline", e.baselineSeries},
                           {"timing", r.timing},
                           {"cases", cases}});
    page << "<h2 id=\"" << e.id << "\">" << escapeHtml(e.title) << "</h2>\n<p>"
         << escapeHtml(e.claim) << " " << escapeHtml(sizes)
         << "</p>\n<table><tr><th>case</th><th>median ms</th><th>min-max ms</th>"
         << "<th>shadow memory MiB</th><th>time / " << escapeHtml(e.baselineSeries)
         << "</th><th>paper</th><th>memory / " << escapeHtml(e.baselineSeries)
         << "</th><th>paper</th></tr>\n";
    for (const CaseMeasurement& m : r.cases) {
      const BenchCase& c = m.benchCase;
      page << "<tr><td>" << escapeHtml(c.label) << "</td><td>" << fixedDigits(m.medianMs, 1)
           << "</td><td>" << fixedDigits(m.minMs, 1) << "-" << fixedDigits(m.maxMs, 1)
           << "</td><td>" << fixedDigits(double(m.shadowBytes) / 1048576.0, 1) << "</td><td>"
           << fixedDigits(m.timeRatio, 2) << "</td><td>"
           << (c.paperTimeRatio ? fixedDigits(*c.paperTimeRatio, 2) : "") << "</td><td>"
           << fixedDigits(m.memoryRatio, 2) << "</td><td>"
           << (c.paperMemoryRatio ? fixedDigits(*c.paperMemoryRatio, 2) : "") << "</td></tr>\n";
    }
    page << "</table>\n";
    for (const CaseMeasurement& m : r.cases) {
      if (!m.benchCase.paperNote.empty()) {
        page << "<p class=\"note\">" << escapeHtml(m.benchCase.label) << ": "
             << escapeHtml(m.benchCase.paperNote) << "</p>\n";
      }
    }
    if (!e.xLabel.empty()) {
      plotSweep(r, dir / "plots" / (e.id + ".png"));
      page << "<p><img src=\"plots/" << e.id << ".png\" alt=\"" << escapeHtml(e.title)
           << "\"></p>\n";
    }
    for (const std::string& line : r.findings) page << "<p>" << escapeHtml(line) << "</p>\n";
  }
  page << "</body></html>\n";
  const ordered_json record = {
      {"device", context.device},   {"timing", results.empty() ? "" : results[0].timing},
      {"scene", context.scene},     {"repeats", context.repeats},
      {"command", context.command}, {"experiments", experiments}};
  writeTextFile(dir / "bench.json", record.dump(2) + "\n");
  writeTextFile(dir / "bench.csv", csv.str());
  writeTextFile(dir / "index.html", page.str());
}

}  // namespace penumbra::compare
