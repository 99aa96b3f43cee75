#include "common/strict_yaml.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace stickrep {

std::string ReadYamlText(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path, 0, "", "no such file (or not a regular file)");
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, 0, "", "cannot read the file size: " + ec.message());
  if (size > kMaxYamlFileBytes) {
    throw InputError(path, 0, "",
                     "file is " + std::to_string(size) + " bytes; a StickRep YAML file may be " +
                         std::to_string(kMaxYamlFileBytes) + " bytes at most");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string YamlQuoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

StrictYaml::StrictYaml(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)),
      file_(std::move(file)),
      path_(std::move(path)),
      used_(std::make_shared<std::set<std::string>>()) {}

StrictYaml StrictYaml::LoadFile(const std::string& path) {
  return LoadString(ReadYamlText(path), path);
}

StrictYaml StrictYaml::LoadString(const std::string& text, const std::string& name) {
  const auto nul = text.find('\0');
  if (nul != std::string::npos) {
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + nul, '\n'));
    throw InputError(name, line, "", "binary data (a NUL byte): not a YAML text file");
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(name, e.mark.line >= 0 ? e.mark.line + 1 : 0, "",
                     "malformed YAML: " + e.msg);
  }
  if (!root.IsMap()) {
    throw InputError(name, 1, "", "the document must be a mapping of keys to values");
  }
  return StrictYaml(root, name, "");
}

int StrictYaml::line() const { return node_.Mark().line >= 0 ? node_.Mark().line + 1 : 0; }

void StrictYaml::RequireMap() const {
  if (!node_.IsMap()) {
    throw InputError(file_, line(), path_, "expected a mapping of keys to values");
  }
}

bool StrictYaml::Has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

std::string StrictYaml::KeyText(const YAML::Node& key) const {
  if (!key.IsScalar()) {
    const int at = key.Mark().line >= 0 ? key.Mark().line + 1 : line();
    throw InputError(file_, at, path_,
                     "a key must be a plain word or number, not a mapping, a sequence or null");
  }
  return key.Scalar();
}

std::vector<std::string> StrictYaml::Keys() const {
  RequireMap();
  std::vector<std::string> keys;
  for (const auto& kv : node_) keys.push_back(KeyText(kv.first));
  return keys;
}

std::string StrictYaml::ChildPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

YAML::Node StrictYaml::Lookup(const std::string& key) const {
  RequireMap();
  used_->insert(key);
  const YAML::Node child = node_[key];
  if (!child.IsDefined() || child.IsNull()) {
    throw InputError(file_, line(), ChildPath(key), "missing required key");
  }
  return child;
}

StrictYaml StrictYaml::Child(const std::string& key) const {
  return StrictYaml(Lookup(key), file_, ChildPath(key));
}

std::vector<StrictYaml> StrictYaml::Sequence(const std::string& key) const {
  return Child(key).Elements();
}

std::vector<StrictYaml> StrictYaml::Elements() const {
  if (!node_.IsSequence()) throw InputError(file_, line(), path_, "expected a sequence");
  std::vector<StrictYaml> out;
  out.reserve(node_.size());
  for (std::size_t i = 0; i < node_.size(); ++i) {
    out.push_back(StrictYaml(node_[i], file_, path_ + "[" + std::to_string(i) + "]"));
  }
  return out;
}

void StrictYaml::Finish() const {
  RequireMap();
  for (const auto& kv : node_) {
    const std::string key = KeyText(kv.first);
    if (used_->count(key) == 0) {
      throw InputError(file_, kv.first.Mark().line + 1, ChildPath(key), "unknown key");
    }
  }
}

void StrictYaml::Fail(const std::string& key, const std::string& reason) const {
  int at = line();
  if (node_.IsMap() && node_[key].IsDefined()) {
    const int l = node_[key].Mark().line;
    if (l >= 0) at = l + 1;
  }
  throw InputError(file_, at, key.empty() ? path_ : ChildPath(key), reason);
}

}  // namespace stickrep
