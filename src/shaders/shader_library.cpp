// Include resolution, #line mapping and variant prefixes for the embedded GLSL.
#include "penumbra/shader_library.h"

#include <algorithm>
#include <regex>
#include <sstream>

#include "penumbra/error.h"

namespace penumbra {
namespace {

constexpr int kMaxIncludeDepth = 32;

std::string directoryOf(std::string_view path) {
  size_t slash = path.rfind('/');
  return slash == std::string_view::npos ? std::string() : std::string(path.substr(0, slash + 1));
}

// "a/b/../c.h" -> "a/c.h"; "./x" -> "x".
std::string normalise(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream in(path);
  std::string part;
  while (std::getline(in, part, '/')) {
    if (part.empty() || part == ".") continue;
    if (part == ".." && !parts.empty() && parts.back() != "..") {
      parts.pop_back();
    } else {
      parts.push_back(part);
    }
  }
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "/") + p;
  return out;
}

class Expander {
 public:
  // amalgamate: each file once (they all have include guards), marked by a comment instead of
  // #line, for hosts that paste the text into their own shaders.
  Expander(const std::map<std::string, std::string, std::less<>>& files, bool amalgamate)
      : files_(files), amalgamate_(amalgamate) {}

  void expandFile(const std::string& path, int depth, const std::string& includer, int line) {
    if (depth > kMaxIncludeDepth) {
      throw Error(includer + ":" + std::to_string(line) + ": includes nest deeper than " +
                  std::to_string(kMaxIncludeDepth) + " (an include cycle?)");
    }
    auto found = files_.find(path);
    if (found == files_.end()) {
      throw Error(
          (includer.empty() ? std::string("shader") : includer + ":" + std::to_string(line)) +
          ": cannot find '" + path + "'");
    }
    if (amalgamate_ && std::find(files_in_order_.begin(), files_in_order_.end(), path) !=
                           files_in_order_.end()) {
      return;
    }
    const int fileIndex = indexOf(path);
    if (amalgamate_) {
      out_ << "// ---- penumbra: " << path << " ----\n";
    } else {
      out_ << "#line 1 " << fileIndex << "\n";
    }
    static const std::regex includeLine(R"re(^\s*#\s*include\s+"([^"]+)"\s*$)re");
    static const std::regex versionLine(R"(^\s*#\s*version\b.*)");
    std::istringstream in(found->second);
    std::string text;
    int lineNumber = 0;
    while (std::getline(in, text)) {
      ++lineNumber;
      std::smatch match;
      if (std::regex_match(text, match, includeLine)) {
        expandFile(resolve(path, match[1].str()), depth + 1, path, lineNumber);
        if (!amalgamate_) out_ << "#line " << lineNumber + 1 << " " << fileIndex << "\n";
      } else if (std::regex_match(text, versionLine)) {
        throw Error(path + ":" + std::to_string(lineNumber) +
                    ": '#version' belongs to the loader; remove it from the file");
      } else {
        out_ << text << "\n";
      }
    }
  }

  ExpandedShader result(std::string prefix) {
    return ExpandedShader{std::move(prefix) + out_.str(), files_in_order_};
  }

 private:
  std::string resolve(const std::string& includer, const std::string& target) const {
    std::string relative = normalise(directoryOf(includer) + target);
    if (files_.count(relative) != 0) return relative;
    return normalise(target);
  }

  int indexOf(const std::string& path) {
    for (size_t i = 0; i < files_in_order_.size(); ++i) {
      if (files_in_order_[i] == path) return int(i);
    }
    files_in_order_.push_back(path);
    return int(files_in_order_.size()) - 1;
  }

  const std::map<std::string, std::string, std::less<>>& files_;
  const bool amalgamate_;
  std::ostringstream out_;
  std::vector<std::string> files_in_order_;
};

}  // namespace

ShaderLibrary::ShaderLibrary() {
  for (const EmbeddedShaderFile& f : embeddedShaderFiles()) {
    files_.emplace(std::string(f.path), std::string(f.source));
  }
}

void ShaderLibrary::addFile(std::string path, std::string source) {
  files_[normalise(path)] = std::move(source);
}

bool ShaderLibrary::contains(std::string_view path) const {
  return files_.find(path) != files_.end();
}

std::vector<std::string> ShaderLibrary::paths() const {
  std::vector<std::string> out;
  for (const auto& [path, source] : files_) out.push_back(path);
  return out;
}

ExpandedShader ShaderLibrary::expand(std::string_view path,
                                     std::span<const ShaderDefine> defines) const {
  std::string prefix = "#version 450 core\n";
  for (const ShaderDefine& d : defines) prefix += "#define " + d.name + " " + d.value + "\n";
  Expander expander(files_, false);
  expander.expandFile(normalise(std::string(path)), 0, "", 0);
  return expander.result(std::move(prefix));
}

std::string ShaderLibrary::amalgamate(std::string_view path) const {
  Expander expander(files_, true);
  expander.expandFile(normalise(std::string(path)), 0, "", 0);
  return expander.result("").source;
}

std::string ExpandedShader::translateLog(std::string_view log) const {
  // Mesa/glslang: "0:12(3): error" or "ERROR: 0:12:"; NVIDIA: "0(12) : error".
  static const std::regex location(R"((\d+)(?::(\d+)|\((\d+)\)))");
  std::string text(log);
  std::string out;
  auto begin = std::sregex_iterator(text.begin(), text.end(), location);
  size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const size_t fileIndex = std::stoul(m[1].str());
    const bool atLineStart = m.position(0) == 0 || text[size_t(m.position(0)) - 1] == '\n' ||
                             text[size_t(m.position(0)) - 1] == ' ';
    if (!atLineStart || fileIndex >= files.size()) continue;
    out += text.substr(last, size_t(m.position(0)) - last);
    out += files[fileIndex] + ":" + (m[2].matched ? m[2].str() : m[3].str());
    last = size_t(m.position(0) + m.length(0));
  }
  out += text.substr(last);
  return out;
}

}  // namespace penumbra
