// Creating the output folder of `render` and `curves`.
#include "output_folder.h"

#include "penumbra/error.h"

namespace penumbra::cli {

void checkOutputPath(const std::string& outDir) {
  if (outDir.empty()) throw Error("the output folder path is empty; name a folder to write to");
}

std::filesystem::path createOutputFolder(const std::string& outDir) {
  checkOutputPath(outDir);
  const std::filesystem::path dir = outDir;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("cannot create output folder " + dir.string() + ": " + ec.message());
  return dir;
}

}  // namespace penumbra::cli
