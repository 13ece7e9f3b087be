#include "climbsim/recording/omgidl_schema.hpp"

#include <cctype>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <stdexcept>

#include "climbsim/foxglove_idl_texts.hpp"
#include "climbsim/idl_texts.hpp"

namespace climbsim::recording {
namespace {

/// One top-level definition inside a module.
struct Definition {
  std::string module;
  std::string name;
  std::string text;  ///< without comments, ending with ';'
};

/// `text` without // and /* */ comments and without preprocessor lines.
std::string stripped(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    if (text.compare(i, 2, "//") == 0) {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (text.compare(i, 2, "/*") == 0) {
      const std::size_t end = text.find("*/", i + 2);
      i = end == std::string::npos ? text.size() : end + 2;
    } else if (text[i] == '#' && (out.empty() || out.back() == '\n')) {
      while (i < text.size() && text[i] != '\n') ++i;
    } else {
      out += text[i++];
    }
  }
  return out;
}

/// The lines of `text` with trailing blanks cut and blank lines dropped, indentation kept.
std::string tidy(const std::string& text) {
  std::string out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos) out += line + "\n";
    start = end + 1;
  }
  return out;
}

std::vector<std::string> identifiers(const std::string& text) {
  static const std::regex word("[A-Za-z_][A-Za-z0-9_]*");
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), word); it != std::sregex_iterator(); ++it) {
    out.push_back(it->str());
  }
  return out;
}

/// The name a definition declares: the identifier after struct/enum/union/bitmask, the one
/// before '=' of a const, the last one of a typedef (before any array bounds).
std::string declaredName(const std::string& text) {
  static const std::regex tagged(R"(\b(struct|enum|union|bitmask)\s+([A-Za-z_]\w*))");
  static const std::regex constant(R"(\bconst\b[^=]*?([A-Za-z_]\w*)\s*=)");
  static const std::regex alias(R"(\btypedef\b.*?([A-Za-z_]\w*)\s*(\[[^\]]*\]\s*)*;\s*$)");
  std::smatch m;
  if (std::regex_search(text, m, constant)) return m[1];
  if (std::regex_search(text, m, alias) && text.find("typedef") < text.find('{')) return m[1];
  if (std::regex_search(text, m, tagged)) return m[2];
  return "";
}

/// Every definition of `file` in order.
std::vector<Definition> definitions(const IdlText& file) {
  const std::string text = stripped(file.second);
  std::vector<Definition> out;
  static const std::regex module_open(R"(\bmodule\s+([A-Za-z_]\w*)\s*\{)");
  auto pos = text.cbegin();
  std::smatch m;
  while (std::regex_search(pos, text.cend(), m, module_open)) {
    const std::string module = m[1];
    std::size_t i = static_cast<std::size_t>(m[0].second - text.cbegin());
    std::size_t start = i;
    int depth = 0;
    for (; i < text.size(); ++i) {
      const char c = text[i];
      if (c == '{') ++depth;
      if (c == '}') {
        if (depth == 0) break;  // the module's closing brace
        --depth;
      }
      if (c == ';' && depth == 0) {
        const std::string def = text.substr(start, i + 1 - start);
        const std::string name = declaredName(def);
        if (name.empty()) {
          throw std::invalid_argument(file.first + ": a definition in module " + module + " declares no name");
        }
        out.push_back({module, name, def});
        start = i + 1;
      }
    }
    if (i >= text.size()) throw std::invalid_argument(file.first + ": module " + module + " is not closed");
    pos = text.cbegin() + static_cast<std::ptrdiff_t>(i + 1);
  }
  return out;
}

}  // namespace

std::vector<IdlText> builtIdlTexts() {
  std::vector<IdlText> out;
  for (const auto& [file, text] : kIdlTexts) out.emplace_back(file, text);
  for (const auto& [file, text] : kFoxgloveIdlTexts) out.emplace_back(file, text);
  return out;
}

namespace {

/// Every definition of a set of IDL files, parsed once, with its index by "module::Name".
struct ParsedIdl {
  std::vector<Definition> all;
  std::map<std::string, std::size_t> by_name;  ///< a forward declaration gives way to the definition
};

ParsedIdl parsed(const std::vector<IdlText>& files) {
  ParsedIdl out;
  for (const auto& f : files) {
    for (auto& d : definitions(f)) out.all.push_back(std::move(d));
  }
  for (std::size_t i = 0; i < out.all.size(); ++i) {
    const std::string key = out.all[i].module + "::" + out.all[i].name;
    if (!out.by_name.count(key) || out.all[i].text.find('{') != std::string::npos) out.by_name[key] = i;
  }
  return out;
}

std::string schemaText(const ParsedIdl& idl, const std::string& type_name) {
  const auto& all = idl.all;
  const auto& by_name = idl.by_name;
  const auto root = by_name.find(type_name);
  if (root == by_name.end()) throw std::invalid_argument("no IDL file defines the type '" + type_name + "'");

  std::vector<std::size_t> order;
  std::set<std::size_t> visited;
  std::function<void(std::size_t)> visit = [&](std::size_t i) {
    if (!visited.insert(i).second) return;
    for (const auto& word : identifiers(all[i].text)) {
      const auto used = by_name.find(all[i].module + "::" + word);
      if (used != by_name.end() && used->second != i) visit(used->second);
    }
    order.push_back(i);
  };
  visit(root->second);

  std::string out;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Definition& d = all[order[k]];
    if (k == 0 || all[order[k - 1]].module != d.module) out += "module " + d.module + " {\n";
    out += tidy(d.text);
    if (k + 1 == order.size() || all[order[k + 1]].module != d.module) out += "};\n";
  }
  return out;
}

}  // namespace

std::string omgidlSchemaText(const std::vector<IdlText>& files, const std::string& type_name) {
  return schemaText(parsed(files), type_name);
}

std::string omgidlSchemaText(const std::string& type_name) {
  // The built files never change: parsed once per process (a recording asks for a dozen types).
  static const ParsedIdl built = parsed(builtIdlTexts());
  return schemaText(built, type_name);
}

}  // namespace climbsim::recording
