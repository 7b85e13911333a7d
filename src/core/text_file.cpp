// Whole-file text output.
#include "penumbra/text_file.h"

#include <fstream>

#include "penumbra/error.h"
#include "penumbra/output_journal.h"

namespace penumbra {

void writeTextFile(const std::filesystem::path& path, std::string_view text) {
  recordOutput(path);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), std::streamsize(text.size()));
  out.close();
  if (!out) throw Error("cannot write " + path.string());
}

}  // namespace penumbra
