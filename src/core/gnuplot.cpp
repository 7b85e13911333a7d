// gnuplot invocation through a temporary script file.
#include "penumbra/gnuplot.h"

#include <sys/wait.h>
#include <unistd.h>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "penumbra/error.h"

namespace penumbra {

std::string gnuplotQuote(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

void runGnuplot(const std::string& script) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path();
  const fs::path scriptPath = dir / ("penumbra-plot-" + std::to_string(getpid()) + ".gp");
  const fs::path logPath = dir / ("penumbra-plot-" + std::to_string(getpid()) + ".log");
  {
    std::ofstream out(scriptPath);
    out << script;
    if (!out) throw Error("cannot write the gnuplot script " + scriptPath.string());
  }
  const std::string command = "gnuplot " + scriptPath.string() + " > " + logPath.string() + " 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream logFile(logPath);
  std::stringstream log;
  log << logFile.rdbuf();
  fs::remove(scriptPath);
  fs::remove(logPath);
  if (status != 0) {
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127) {
      throw Error(
          "gnuplot is not installed: run scripts/install-deps (Debian package gnuplot-nox)");
    }
    throw Error("gnuplot failed: " + log.str());
  }
}

}  // namespace penumbra
