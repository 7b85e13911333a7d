// One journal per process: the commands write one output folder at a time.
#include "penumbra/output_journal.h"

#include <fstream>
#include <mutex>
#include <set>
#include <string>

#include "penumbra/error.h"

namespace penumbra {
namespace fs = std::filesystem;

namespace {

struct Journal {
  std::mutex mutex;
  fs::path folder;  // absolute, normal; empty when no journal is open
  fs::path file;
  std::set<std::string> listed;
};

Journal& journal() {
  static Journal instance;
  return instance;
}

}  // namespace

void startOutputJournal(const fs::path& folder, const fs::path& file) {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  j.folder = fs::absolute(folder).lexically_normal();
  j.file = file;
  j.listed.clear();
}

void stopOutputJournal() noexcept {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  j.folder.clear();
  j.file.clear();
  j.listed.clear();
}

void recordOutput(const fs::path& path) {
  Journal& j = journal();
  std::lock_guard lock(j.mutex);
  if (j.folder.empty()) return;
  const fs::path relative = fs::absolute(path).lexically_normal().lexically_relative(j.folder);
  if (relative.empty() || *relative.begin() == ".." || *relative.begin() == ".") return;
  if (relative.string().find('\n') != std::string::npos) {
    throw Error("cannot write " + path.string() +
                ": its name holds a line break, which the output folder's list cannot carry");
  }
  std::string lines;
  fs::path prefix;
  for (const fs::path& part : relative) {
    prefix /= part;
    const std::string entry = prefix.generic_string();
    if (j.listed.insert(entry).second) lines += "entry " + entry + "\n";
  }
  if (lines.empty()) return;
  std::ofstream out(j.file, std::ios::app);
  out << lines;
  out.close();
  if (!out) throw Error("cannot list " + path.string() + " in " + j.file.string());
}

void createOutputDirectory(const fs::path& path) {
  recordOutput(path);
  std::error_code ec;
  {
    // A staging folder removed under a writer (an interrupt) must stay removed, not come back
    // without its marker: missing parents are created only inside a journalled folder that
    // still exists.
    Journal& j = journal();
    std::lock_guard lock(j.mutex);
    if (!j.folder.empty() && !fs::is_directory(j.folder, ec)) {
      throw Error("cannot create " + path.string() + ": the output folder being written is gone");
    }
  }
  fs::create_directories(path, ec);
  if (ec) throw Error("cannot create " + path.string() + ": " + ec.message());
}

}  // namespace penumbra
