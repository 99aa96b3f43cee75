// idl_json_gen: reads the StickRep IDL files and writes the JSON form of every type they
// define (nlohmann-json to_json and from_json for each struct and enum, a name function per
// enum) and a description of every type (idl_json.h).
//
//   idl_json_gen --header OUT.h --source OUT.cpp [-I DIR]... FILE.idl...
//
// It reads the subset of OMG IDL 4 StickRep uses: #include, modules, enums, structs whose
// members are of the primitive types (boolean, octet, char, [unsigned] short, [unsigned] long,
// [unsigned] long long, float, double), string, string<N>, sequence<T> and sequence<T, N>,
// arrays (T name[N]...), or of an enum or struct declared before; // and /* */ comments; and
// @key on members. Anything else is an error naming the file and line, and nothing is written.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "idl_json.h"

namespace fs = std::filesystem;

namespace {

// An error at a place in an IDL file.
class IdlError : public std::runtime_error {
 public:
  IdlError(const std::string& file, int line, const std::string& reason)
      : std::runtime_error(file + ":" + std::to_string(line) + ": error: " + reason) {}
};

// ---------------------------------------------------------------------------------------------
// Tokens

struct Token {
  enum class Kind { kIdentifier, kInteger, kPunct, kInclude, kEnd };
  Kind kind = Kind::kEnd;
  std::string text;  // an identifier, the digits, the punctuation, an #include's file name
  int line = 0;
};

bool IsIdentifierStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsIdentifierChar(char c) { return IsIdentifierStart(c) || IsDigit(c); }
bool IsHexDigit(char c) { return IsDigit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }

std::vector<Token> Lex(const std::string& file, const std::string& text) {
  std::vector<Token> tokens;
  int line = 1;
  bool line_start = true;  // only whitespace since the last newline
  std::size_t i = 0;
  const auto fail = [&](const std::string& reason) { throw IdlError(file, line, reason); };
  const auto at = [&](std::size_t k) { return k < text.size() ? text[k] : '\0'; };
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      line++;
      line_start = true;
      i++;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      i++;
      continue;
    }
    if (c == '/' && at(i + 1) == '/') {
      while (i < text.size() && text[i] != '\n') i++;
      continue;
    }
    if (c == '/' && at(i + 1) == '*') {
      const int start = line;
      i += 2;
      while (i < text.size() && !(text[i] == '*' && at(i + 1) == '/')) {
        if (text[i] == '\n') line++;
        i++;
      }
      if (i >= text.size()) throw IdlError(file, start, "unterminated /* comment");
      i += 2;
      continue;
    }
    if (c == '#') {
      if (!line_start) fail("'#' not at the start of a line");
      i++;
      while (at(i) == ' ' || at(i) == '\t') i++;
      std::string directive;
      while (IsIdentifierChar(at(i))) directive += text[i++];
      if (directive != "include") {
        fail("preprocessor directive #" + directive + " is not supported (only #include)");
      }
      while (at(i) == ' ' || at(i) == '\t') i++;
      const char open = at(i);
      if (open != '"' && open != '<') fail("#include without a \"file\" or <file>");
      const char close = open == '"' ? '"' : '>';
      std::string name;
      for (i++; at(i) != close; i++) {
        if (at(i) == '\n' || at(i) == '\0') fail("unterminated #include file name");
        name += text[i];
      }
      i++;
      while (at(i) == ' ' || at(i) == '\t' || at(i) == '\r') i++;
      if (at(i) == '/' && at(i + 1) == '/') {
        while (i < text.size() && text[i] != '\n') i++;
      }
      if (at(i) != '\n' && at(i) != '\0') fail("text after #include \"" + name + "\"");
      tokens.push_back({Token::Kind::kInclude, name, line});
      continue;
    }
    line_start = false;
    if (IsIdentifierStart(c)) {
      if (c == '_') fail("escaped identifiers (a leading '_') are not supported");
      std::string word;
      while (IsIdentifierChar(at(i))) word += text[i++];
      tokens.push_back({Token::Kind::kIdentifier, word, line});
      continue;
    }
    if (IsDigit(c)) {
      std::string digits;
      if (c == '0' && (at(i + 1) == 'x' || at(i + 1) == 'X')) {
        i += 2;
        while (IsHexDigit(at(i))) digits += text[i++];
        if (digits.empty()) fail("a hexadecimal literal without digits");
        if (digits.size() > 8) fail("hexadecimal literal 0x" + digits + " is too large");
        digits = std::to_string(std::stoull(digits, nullptr, 16));
      } else {
        while (IsDigit(at(i))) digits += text[i++];
        if (digits.size() > 1 && digits[0] == '0') fail("octal literals are not supported");
      }
      if (IsIdentifierChar(at(i)) || at(i) == '.') {
        fail("only integer literals are supported (found '" + digits + at(i) + "...')");
      }
      if (digits.size() > 10) fail("integer literal " + digits + " is too large");
      tokens.push_back({Token::Kind::kInteger, digits, line});
      continue;
    }
    if (c == ':' && at(i + 1) == ':') {
      tokens.push_back({Token::Kind::kPunct, "::", line});
      i += 2;
      continue;
    }
    if (std::string("{}[]<>;,:@()=").find(c) != std::string::npos) {
      tokens.push_back({Token::Kind::kPunct, std::string(1, c), line});
      i++;
      continue;
    }
    if (c == '"' || c == '\'') fail("string and character literals are not supported");
    fail(std::string("unexpected character '") + c + "'");
  }
  tokens.push_back({Token::Kind::kEnd, "", line});
  return tokens;
}

// ---------------------------------------------------------------------------------------------
// The model: what the files define

using stickrep::idl::Kind;

struct TypeNode {
  Kind kind = Kind::kBoolean;
  std::string name;         // scoped name of an enum or a struct: "stickrep::msgs::Pose2D"
  std::uint32_t bound = 0;  // a sequence's or string's bound (0: unbounded); an array's length
  std::shared_ptr<const TypeNode> element;
};

struct MemberDef {
  std::string name;
  TypeNode type;
  bool key = false;
};

struct StructDef {
  std::string name;  // scoped
  std::string file;  // file name, e.g. "sensors.idl"
  std::vector<MemberDef> members;
};

struct EnumDef {
  std::string name;  // scoped
  std::string file;
  std::vector<std::string> enumerators;
};

struct Model {
  std::vector<std::string> files;  // file names in the order they were read
  std::vector<StructDef> structs;
  std::vector<EnumDef> enums;
  // Every name declared in a module, scoped, with what it is and where.
  struct Declaration {
    enum class What { kStruct, kEnum, kEnumerator } what;
    std::string where;  // file:line
  };
  std::map<std::string, Declaration> declared;
};

std::string Join(const std::vector<std::string>& scope, const std::string& name) {
  std::string out;
  for (const auto& s : scope) out += s + "::";
  return out + name;
}

// ---------------------------------------------------------------------------------------------
// The parser

class Parser {
 public:
  Parser(Model& model, std::vector<fs::path> include_dirs)
      : model_(model), include_dirs_(std::move(include_dirs)) {}

  // Reads a file and, first, the files it includes; a file already read is skipped.
  void ParseFile(const fs::path& path, const std::string& included_from) {
    const fs::path canonical = fs::weakly_canonical(path);
    if (!read_.insert(canonical.string()).second) return;
    std::ifstream in(canonical, std::ios::binary);
    if (!in) throw std::runtime_error(included_from + "error: cannot read " + path.string());
    std::stringstream text;
    text << in.rdbuf();
    model_.files.push_back(canonical.filename().string());
    File f{canonical, canonical.filename().string(), Lex(path.string(), text.str()), 0,
           path.string()};
    files_.push_back(&f);
    ParseDefinitions({}, /*in_module=*/false);
    files_.pop_back();
  }

 private:
  struct File {
    fs::path path;
    std::string name;  // "sensors.idl"
    std::vector<Token> tokens;
    std::size_t pos;
    std::string display;  // the path as errors print it
  };

  File& file() { return *files_.back(); }
  const Token& Peek(std::size_t ahead = 0) {
    const auto& t = file().tokens;
    return t[std::min(file().pos + ahead, t.size() - 1)];
  }
  const Token& Next() {
    const Token& t = Peek();
    if (t.kind != Token::Kind::kEnd) file().pos++;
    return t;
  }
  [[noreturn]] void Fail(const std::string& reason, int line = 0) {
    throw IdlError(file().display, line != 0 ? line : Peek().line, reason);
  }
  static std::string Describe(const Token& t) {
    switch (t.kind) {
      case Token::Kind::kEnd:
        return "the end of the file";
      case Token::Kind::kInclude:
        return "#include \"" + t.text + "\"";
      default:
        return "'" + t.text + "'";
    }
  }
  bool IsPunct(const Token& t, const char* p) {
    return t.kind == Token::Kind::kPunct && t.text == p;
  }
  bool IsWord(const Token& t, const char* w) {
    return t.kind == Token::Kind::kIdentifier && t.text == w;
  }
  void Expect(const char* punct, const std::string& context) {
    if (!IsPunct(Peek(), punct)) {
      Fail("expected '" + std::string(punct) + "' " + context + ", found " + Describe(Peek()));
    }
    Next();
  }
  std::string ExpectIdentifier(const std::string& what) {
    const Token& t = Peek();
    if (t.kind != Token::Kind::kIdentifier) Fail("expected " + what + ", found " + Describe(t));
    if (IsKeyword(t.text)) Fail("expected " + what + ", found the keyword '" + t.text + "'");
    return Next().text;
  }
  std::uint32_t ExpectPositiveInteger(const std::string& what) {
    const Token& t = Peek();
    if (t.kind != Token::Kind::kInteger) {
      Fail("expected " + what +
           " (an integer literal; constants and expressions are not "
           "supported), found " +
           Describe(t));
    }
    const unsigned long long v = std::stoull(t.text);
    if (v == 0 || v > 0xffffffffull) Fail(what + " " + t.text + " is not in 1..4294967295");
    Next();
    return static_cast<std::uint32_t>(v);
  }

  static bool IsKeyword(const std::string& w) {
    static const std::set<std::string> keywords = {
        "abstract",   "any",       "attribute",   "bitmask",   "bitset",    "boolean",
        "case",       "char",      "component",   "const",     "consumes",  "context",
        "custom",     "default",   "double",      "emits",     "enum",      "eventtype",
        "exception",  "factory",   "FALSE",       "finder",    "fixed",     "float",
        "getraises",  "home",      "import",      "in",        "inout",     "interface",
        "local",      "long",      "manages",     "map",       "module",    "multiple",
        "native",     "Object",    "octet",       "oneway",    "out",       "primarykey",
        "private",    "provides",  "public",      "publishes", "raises",    "readonly",
        "sequence",   "setraises", "short",       "string",    "struct",    "supports",
        "switch",     "TRUE",      "truncatable", "typedef",   "typeid",    "typename",
        "typeprefix", "unsigned",  "union",       "uses",      "ValueBase", "valuetype",
        "void",       "wchar",     "wstring",     "int8",      "uint8",     "int16",
        "int32",      "int64",     "uint16",      "uint32",    "uint64"};
    return keywords.count(w) > 0;
  }

  void Declare(const std::string& scoped, Model::Declaration::What what, int line) {
    const std::string where = file().display + ":" + std::to_string(line);
    const auto [it, added] = model_.declared.emplace(scoped, Model::Declaration{what, where});
    if (!added) Fail("'" + scoped + "' is already declared at " + it->second.where, line);
  }

  void ParseDefinitions(const std::vector<std::string>& scope, bool in_module) {
    while (true) {
      const Token& t = Peek();
      if (t.kind == Token::Kind::kEnd) {
        if (in_module) Fail("the file ends inside module " + Join(scope, ""));
        return;
      }
      if (in_module && IsPunct(t, "}")) return;
      if (t.kind == Token::Kind::kInclude) {
        if (in_module) Fail("#include inside a module is not supported");
        IncludeFile(Next());
      } else if (IsWord(t, "module")) {
        Next();
        const std::string name = ExpectIdentifier("a module name");
        auto inner = scope;
        inner.push_back(name);
        Expect("{", "after module " + name);
        ParseDefinitions(inner, /*in_module=*/true);
        Expect("}", "closing module " + name);
        Expect(";", "after the '}' of module " + name);
      } else if (IsWord(t, "struct")) {
        ParseStruct(scope);
      } else if (IsWord(t, "enum")) {
        ParseEnum(scope);
      } else if (IsPunct(t, "@")) {
        Next();
        Fail("annotation @" + Peek().text + " is not supported here (only @key, on members)");
      } else if (t.kind == Token::Kind::kIdentifier && IsKeyword(t.text)) {
        Fail("'" + t.text + "' definitions are not supported (only module, struct and enum)");
      } else {
        Fail("expected a module, struct or enum definition, found " + Describe(t));
      }
    }
  }

  void IncludeFile(const Token& include) {
    std::vector<fs::path> candidates = {file().path.parent_path() / include.text};
    for (const auto& dir : include_dirs_) candidates.push_back(dir / include.text);
    for (const auto& c : candidates) {
      if (fs::is_regular_file(c)) {
        ParseFile(c, file().display + ":" + std::to_string(include.line) + ": ");
        return;
      }
    }
    Fail("cannot find the included file \"" + include.text + "\"", include.line);
  }

  void ParseStruct(const std::vector<std::string>& scope) {
    Next();  // struct
    const int line = Peek().line;
    const std::string name = ExpectIdentifier("a struct name");
    if (IsPunct(Peek(), ";")) Fail("forward declarations are not supported");
    if (IsPunct(Peek(), ":")) Fail("struct inheritance is not supported");
    Expect("{", "after struct " + name);
    StructDef s;
    s.name = Join(scope, name);
    s.file = file().name;
    std::set<std::string> member_names;
    while (!IsPunct(Peek(), "}")) {
      if (Peek().kind == Token::Kind::kEnd) Fail("the file ends inside struct " + name);
      bool key = false;
      while (IsPunct(Peek(), "@")) {
        Next();
        const std::string annotation = Peek().kind == Token::Kind::kIdentifier ? Next().text : "";
        if (annotation != "key") {
          Fail("annotation @" + annotation + " is not supported (only @key)");
        }
        if (IsPunct(Peek(), "(")) Fail("annotation parameters are not supported (write @key)");
        key = true;
      }
      const TypeNode base = ParseType(scope);
      while (true) {
        const int member_line = Peek().line;
        const std::string member = ExpectIdentifier("a member name");
        std::vector<std::uint32_t> dims;
        while (IsPunct(Peek(), "[")) {
          Next();
          dims.push_back(ExpectPositiveInteger("an array length"));
          Expect("]", "after an array length");
        }
        TypeNode type = base;
        for (auto d = dims.rbegin(); d != dims.rend(); ++d) {
          TypeNode array;
          array.kind = Kind::kArray;
          array.bound = *d;
          array.element = std::make_shared<const TypeNode>(std::move(type));
          type = std::move(array);
        }
        if (!member_names.insert(member).second) {
          Fail("member '" + member + "' of struct " + name + " is declared twice", member_line);
        }
        s.members.push_back({member, std::move(type), key});
        if (IsPunct(Peek(), ",")) {
          Next();
          continue;
        }
        Expect(";", "after member " + member);
        break;
      }
    }
    Next();  // }
    Expect(";", "after the '}' of struct " + name);
    Declare(s.name, Model::Declaration::What::kStruct, line);
    model_.structs.push_back(std::move(s));
  }

  void ParseEnum(const std::vector<std::string>& scope) {
    Next();  // enum
    const int line = Peek().line;
    const std::string name = ExpectIdentifier("an enum name");
    Expect("{", "after enum " + name);
    EnumDef e;
    e.name = Join(scope, name);
    e.file = file().name;
    while (true) {
      if (IsPunct(Peek(), "@")) Fail("annotations on enumerators are not supported");
      const int enumerator_line = Peek().line;
      const std::string enumerator = ExpectIdentifier("an enumerator of " + name);
      Declare(Join(scope, enumerator), Model::Declaration::What::kEnumerator, enumerator_line);
      e.enumerators.push_back(enumerator);
      if (IsPunct(Peek(), ",")) {
        Next();
        continue;
      }
      if (IsPunct(Peek(), "=")) Fail("enumerator values are not supported");
      Expect("}", "after the enumerators of " + name);
      break;
    }
    Expect(";", "after the '}' of enum " + name);
    Declare(e.name, Model::Declaration::What::kEnum, line);
    model_.enums.push_back(std::move(e));
  }

  TypeNode Basic(Kind kind) {
    TypeNode t;
    t.kind = kind;
    return t;
  }
  // Consumes the current token, the last of the type.
  TypeNode Take(Kind kind) {
    Next();
    return Basic(kind);
  }

  TypeNode ParseType(const std::vector<std::string>& scope) {
    const Token& t = Peek();
    if (t.kind != Token::Kind::kIdentifier && !IsPunct(t, "::")) {
      Fail("expected a member type, found " + Describe(t));
    }
    const std::string w = t.text;
    if (w == "boolean") return Take(Kind::kBoolean);
    if (w == "octet") return Take(Kind::kOctet);
    if (w == "char") return Take(Kind::kChar);
    if (w == "short") return Take(Kind::kShort);
    if (w == "float") return Take(Kind::kFloat);
    if (w == "double") return Take(Kind::kDouble);
    if (w == "unsigned") {
      Next();
      if (IsWord(Peek(), "short")) return Take(Kind::kUnsignedShort);
      if (!IsWord(Peek(), "long")) Fail("expected 'short' or 'long' after 'unsigned'");
      Next();
      if (IsWord(Peek(), "long")) return Take(Kind::kUnsignedLongLong);
      return Basic(Kind::kUnsignedLong);
    }
    if (w == "long") {
      Next();
      if (IsWord(Peek(), "double")) Fail("type 'long double' is not supported");
      if (IsWord(Peek(), "long")) return Take(Kind::kLongLong);
      return Basic(Kind::kLong);
    }
    if (w == "string") {
      Next();
      TypeNode s = Basic(Kind::kString);
      if (IsPunct(Peek(), "<")) {
        Next();
        s.bound = ExpectPositiveInteger("a string bound");
        Expect(">", "after the string bound");
      }
      return s;
    }
    if (w == "sequence") {
      Next();
      Expect("<", "after 'sequence'");
      TypeNode seq = Basic(Kind::kSequence);
      seq.element = std::make_shared<const TypeNode>(ParseType(scope));
      if (IsPunct(Peek(), ",")) {
        Next();
        seq.bound = ExpectPositiveInteger("a sequence bound");
      }
      Expect(">", "closing the sequence");
      return seq;
    }
    if (t.kind == Token::Kind::kIdentifier && IsKeyword(w)) {
      Fail("type '" + w +
           "' is not supported (boolean, octet, char, [unsigned] short, "
           "[unsigned] long, [unsigned] long long, float, double, string, sequence, or an enum "
           "or struct)");
    }
    return ParseNamedType(scope);
  }

  // A struct or enum by (scoped) name, looked up from the innermost module outwards.
  TypeNode ParseNamedType(const std::vector<std::string>& scope) {
    const int line = Peek().line;
    bool absolute = false;
    if (IsPunct(Peek(), "::")) {
      absolute = true;
      Next();
    }
    std::string written = ExpectIdentifier("a type name");
    while (IsPunct(Peek(), "::")) {
      Next();
      written += "::" + ExpectIdentifier("a type name after '::'");
    }
    std::vector<std::string> candidates;
    if (absolute) {
      candidates.push_back(written);
    } else {
      for (std::size_t n = scope.size() + 1; n-- > 0;) {
        candidates.push_back(Join({scope.begin(), scope.begin() + n}, written));
      }
    }
    for (const auto& c : candidates) {
      const auto it = model_.declared.find(c);
      if (it == model_.declared.end()) continue;
      using What = Model::Declaration::What;
      if (it->second.what == What::kEnumerator) {
        Fail("'" + written + "' is an enumerator, not a type", line);
      }
      TypeNode t = Basic(it->second.what == What::kStruct ? Kind::kStruct : Kind::kEnum);
      t.name = c;
      return t;
    }
    Fail("unknown type '" + written + "' (types must be declared before use)", line);
  }

  Model& model_;
  std::vector<fs::path> include_dirs_;
  std::set<std::string> read_;
  std::vector<File*> files_;
};

// ---------------------------------------------------------------------------------------------
// The emitter

std::string KindName(Kind k) {
  switch (k) {
    case Kind::kBoolean:
      return "kBoolean";
    case Kind::kOctet:
      return "kOctet";
    case Kind::kChar:
      return "kChar";
    case Kind::kShort:
      return "kShort";
    case Kind::kUnsignedShort:
      return "kUnsignedShort";
    case Kind::kLong:
      return "kLong";
    case Kind::kUnsignedLong:
      return "kUnsignedLong";
    case Kind::kLongLong:
      return "kLongLong";
    case Kind::kUnsignedLongLong:
      return "kUnsignedLongLong";
    case Kind::kFloat:
      return "kFloat";
    case Kind::kDouble:
      return "kDouble";
    case Kind::kString:
      return "kString";
    case Kind::kEnum:
      return "kEnum";
    case Kind::kStruct:
      return "kStruct";
    case Kind::kSequence:
      return "kSequence";
    case Kind::kArray:
      return "kArray";
  }
  return "";
}

// As IDL spells the type (with scoped names), for error messages.
std::string Spell(const TypeNode& t) {
  switch (t.kind) {
    case Kind::kString:
      return t.bound ? "string<" + std::to_string(t.bound) + ">" : "string";
    case Kind::kEnum:
    case Kind::kStruct:
      return t.name;
    case Kind::kSequence:
      return "sequence<" + Spell(*t.element) + (t.bound ? ", " + std::to_string(t.bound) : "") +
             ">";
    case Kind::kArray: {
      std::string e = Spell(*t.element);
      const std::size_t dims = t.element->kind == Kind::kArray ? e.find('[') : e.size();
      return e.insert(dims, "[" + std::to_string(t.bound) + "]");
    }
    default:  // the basic kinds
      return stickrep::idl::KindSpelling(t.kind);
  }
}

// The C++ type fastddsgen gives a member of this type.
std::string CppType(const TypeNode& t) {
  switch (t.kind) {
    case Kind::kBoolean:
      return "bool";
    case Kind::kOctet:
      return "std::uint8_t";
    case Kind::kChar:
      return "char";
    case Kind::kShort:
      return "std::int16_t";
    case Kind::kUnsignedShort:
      return "std::uint16_t";
    case Kind::kLong:
      return "std::int32_t";
    case Kind::kUnsignedLong:
      return "std::uint32_t";
    case Kind::kLongLong:
      return "std::int64_t";
    case Kind::kUnsignedLongLong:
      return "std::uint64_t";
    case Kind::kFloat:
      return "float";
    case Kind::kDouble:
      return "double";
    case Kind::kString:
      return t.bound ? "eprosima::fastrtps::fixed_string<" + std::to_string(t.bound) + ">"
                     : "std::string";
    case Kind::kEnum:
    case Kind::kStruct:
      return "::" + t.name;
    case Kind::kSequence:
      return "std::vector<" + CppType(*t.element) + ">";
    case Kind::kArray:
      return "std::array<" + CppType(*t.element) + ", " + std::to_string(t.bound) + ">";
  }
  return "";
}

// The description's expression for the type.
std::string TypeExpr(const TypeNode& t) {
  switch (t.kind) {
    case Kind::kEnum:
    case Kind::kStruct:
      return "NamedType(Kind::" + KindName(t.kind) + ", \"" + t.name + "\")";
    case Kind::kString:
      return "StringType(" + std::to_string(t.bound) + ")";
    case Kind::kSequence:
      return "SequenceType(" + TypeExpr(*t.element) + ", " + std::to_string(t.bound) + ")";
    case Kind::kArray:
      return "ArrayType(" + TypeExpr(*t.element) + ", " + std::to_string(t.bound) + ")";
    default:
      return "BasicType(Kind::" + KindName(t.kind) + ")";
  }
}

bool IsOctetSequence(const TypeNode& t) {
  return t.kind == Kind::kSequence && t.element->kind == Kind::kOctet;
}

// An expression: the JSON form of `value`.
std::string WriteExpr(const TypeNode& t, const std::string& value, int depth) {
  if (IsOctetSequence(t)) return "codec::WriteBytes(" + value + ")";
  if (t.kind == Kind::kSequence || t.kind == Kind::kArray) {
    const std::string e = "e" + std::to_string(depth);
    return "codec::WriteSequence(" + value + ", [](const auto& " + e + ") { return " +
           WriteExpr(*t.element, e, depth + 1) + "; })";
  }
  return "codec::Write(" + value + ")";
}

// A statement: reads `json` into `value`.
std::string ReadStmt(const TypeNode& t, const std::string& json, const std::string& value,
                     int depth) {
  const std::string spelled = "\"" + Spell(t) + "\"";
  if (IsOctetSequence(t)) {
    return "codec::ReadBytes(" + json + ", " + value + ", " + std::to_string(t.bound) + ", " +
           spelled + ")";
  }
  if (t.kind == Kind::kSequence || t.kind == Kind::kArray) {
    const std::string j = "j" + std::to_string(depth), e = "e" + std::to_string(depth);
    const std::string read = "[](const nlohmann::json& " + j + ", auto& " + e + ") { " +
                             ReadStmt(*t.element, j, e, depth + 1) + "; }";
    if (t.kind == Kind::kSequence) {
      return "codec::ReadSequence(" + json + ", " + value + ", " + std::to_string(t.bound) + ", " +
             spelled + ", " + read + ")";
    }
    return "codec::ReadArray(" + json + ", " + value + ", " + spelled + ", " + read + ")";
  }
  return "codec::Read(" + json + ", " + value + ")";
}

// "stickrep::msgs::Pose2D" -> namespace "stickrep::msgs", name "Pose2D".
std::pair<std::string, std::string> SplitScoped(const std::string& scoped) {
  const std::size_t at = scoped.rfind("::");
  if (at == std::string::npos) return {"", scoped};
  return {scoped.substr(0, at), scoped.substr(at + 2)};
}

std::string FileList(const Model& m) {
  std::string out;
  for (const auto& f : m.files) out += (out.empty() ? "" : ", ") + f;
  return out;
}

std::string EmitHeader(const Model& m) {
  std::ostringstream h;
  h << "// Generated by idl_json_gen from " << FileList(m) << "; do not edit.\n"
    << "// The JSON form of every IDL type (see idl_json_codec.h for the form) and a description\n"
    << "// of every type.\n"
    << "#pragma once\n\n"
    << "#include <nlohmann/json.hpp>\n\n"
    << "#include <string>\n#include <string_view>\n#include <vector>\n\n"
    << "#include \"idl_json.h\"\n";
  for (const auto& f : m.files) h << "#include \"" << fs::path(f).stem().string() << ".h\"\n";
  h << "\n";

  // Declarations, namespace by namespace in IDL order.
  std::string open_ns;
  const auto enter = [&](const std::string& ns) {
    if (ns == open_ns) return;
    if (!open_ns.empty()) h << "}  // namespace " << open_ns << "\n\n";
    if (!ns.empty()) h << "namespace " << ns << " {\n\n";
    open_ns = ns;
  };
  for (const auto& e : m.enums) {
    const auto [ns, name] = SplitScoped(e.name);
    enter(ns);
    h << "// enum " << e.name << " (" << e.file << ")\n"
      << "// Its name as the IDL spells it; \"?\" for a value outside the enum.\n"
      << "const char* EnumName(" << name << " value);\n"
      << "// False, leaving *value as it was, for a name that is not one of its enumerators.\n"
      << "bool EnumFromName(std::string_view name, " << name << "* value);\n"
      << "void to_json(nlohmann::json& j, const " << name << "& value);\n"
      << "void from_json(const nlohmann::json& j, " << name << "& value);\n\n";
  }
  for (const auto& s : m.structs) {
    const auto [ns, name] = SplitScoped(s.name);
    enter(ns);
    h << "// struct " << s.name << " (" << s.file << ")\n"
      << "void to_json(nlohmann::json& j, const " << name << "& value);\n"
      << "// Throws stickrep::idl::JsonFormError; `value` may then be partly assigned.\n"
      << "void from_json(const nlohmann::json& j, " << name << "& value);\n\n";
  }
  enter("");

  h << "namespace stickrep::idl {\n\n"
    << "// Every struct and every enum of the IDL files, in the order they are defined.\n"
    << "const std::vector<Struct>& Structs();\n"
    << "const std::vector<Enum>& Enums();\n"
    << "// By scoped name (\"stickrep::msgs::Pose2D\"); nullptr for a name not defined.\n"
    << "const Struct* FindStruct(std::string_view name);\n"
    << "const Enum* FindEnum(std::string_view name);\n\n"
    << "// The scoped IDL name of a generated type: TypeName<msgs::Pose2D>::value.\n";
  for (const auto& s : m.structs) {
    h << "template <>\nstruct TypeName<::" << s.name << "> {\n"
      << "  static constexpr const char* value = \"" << s.name << "\";\n};\n";
  }
  for (const auto& e : m.enums) {
    h << "template <>\nstruct TypeName<::" << e.name << "> {\n"
      << "  static constexpr const char* value = \"" << e.name << "\";\n};\n";
  }
  h << "\n// Calls visitor(TypeTag<T>{}, description) for every struct T, in IDL order.\n"
    << "template <typename Visitor>\nvoid ForEachStruct(Visitor&& visitor) {\n";
  for (std::size_t i = 0; i < m.structs.size(); ++i) {
    h << "  visitor(TypeTag<::" << m.structs[i].name << ">{}, Structs()[" << i << "]);\n";
  }
  h << "}\n\n}  // namespace stickrep::idl\n";
  return h.str();
}

std::string EmitSource(const Model& m) {
  std::ostringstream c;
  c << "// Generated by idl_json_gen from " << FileList(m) << "; do not edit.\n"
    << "#include \"msgs_json.h\"\n\n"
    << "#include <array>\n#include <cstdint>\n#include <string>\n#include <type_traits>\n"
    << "#include <utility>\n#include <vector>\n\n"
    << "#include \"idl_json_codec.h\"\n\n";

  // fastddsgen's C++ types are the ones the description says.
  c << "namespace {\n\n";
  for (const auto& s : m.structs) {
    for (const auto& mem : s.members) {
      c << "static_assert(std::is_same_v<std::decay_t<decltype(std::declval<const ::" << s.name
        << "&>()." << mem.name << "())>, " << CppType(mem.type) << ">,\n"
        << "              \"fastddsgen's C++ type of " << s.name << "." << mem.name << " is not "
        << CppType(mem.type) << "\");\n";
    }
  }
  c << "\n}  // namespace\n\n";

  std::string open_ns;
  const auto enter = [&](const std::string& ns) {
    if (ns == open_ns) return;
    if (!open_ns.empty()) c << "}  // namespace " << open_ns << "\n\n";
    if (!ns.empty()) c << "namespace " << ns << " {\n\n";
    if (!ns.empty()) c << "namespace codec = ::stickrep::idl::codec;\n\n";
    open_ns = ns;
  };
  for (const auto& e : m.enums) {
    const auto [ns, name] = SplitScoped(e.name);
    enter(ns);
    std::string names;
    for (const auto& n : e.enumerators) names += (names.empty() ? "" : ", ") + n;
    c << "const char* EnumName(" << name << " value) {\n  switch (value) {\n";
    for (const auto& n : e.enumerators) {
      c << "    case " << name << "::" << n << ": return \"" << n << "\";\n";
    }
    c << "  }\n  return \"?\";\n}\n\n"
      << "bool EnumFromName(std::string_view name, " << name << "* value) {\n";
    for (const auto& n : e.enumerators) {
      c << "  if (name == \"" << n << "\") {\n    *value = " << name << "::" << n
        << ";\n    return true;\n  }\n";
    }
    c << "  return false;\n}\n\n"
      << "void to_json(nlohmann::json& j, const " << name << "& value) {\n"
      << "  const char* name = EnumName(value);\n"
      << "  if (name[0] != '?') {\n    j = name;\n  } else {\n"
      << "    j = static_cast<std::underlying_type_t<" << name << ">>(value);\n  }\n}\n\n"
      << "void from_json(const nlohmann::json& j, " << name << "& value) {\n"
      << "  if (!j.is_string() || !EnumFromName(j.get_ref<const std::string&>(), &value)) {\n"
      << "    throw codec::NotAnEnumerator(j, \"" << e.name << "\", \"" << names << "\");\n"
      << "  }\n}\n\n";
  }
  for (const auto& s : m.structs) {
    const auto [ns, name] = SplitScoped(s.name);
    enter(ns);
    c << "void to_json(nlohmann::json& j, const " << name << "& value) {\n"
      << "  j = nlohmann::json::object();\n";
    for (const auto& mem : s.members) {
      c << "  j[\"" << mem.name << "\"] = " << WriteExpr(mem.type, "value." + mem.name + "()", 0)
        << ";\n";
    }
    c << "}\n\n"
      << "void from_json(const nlohmann::json& j, " << name << "& value) {\n"
      << "  codec::CheckObject(j, \"" << s.name << "\", {";
    for (std::size_t i = 0; i < s.members.size(); ++i) {
      c << (i ? ", " : "") << "\"" << s.members[i].name << "\"";
    }
    c << "});\n";
    for (const auto& mem : s.members) {
      c << "  codec::ReadMember(j, \"" << mem.name << "\", [&](const nlohmann::json& m) { "
        << ReadStmt(mem.type, "m", "value." + mem.name + "()", 0) << "; });\n";
    }
    c << "}\n\n";
  }
  enter("");

  c << "namespace stickrep::idl {\n\n"
    << "const std::vector<Struct>& Structs() {\n"
    << "  static const std::vector<Struct> structs = {\n";
  for (const auto& s : m.structs) {
    c << "      {\"" << s.name << "\", \"" << s.file << "\", {\n";
    for (const auto& mem : s.members) {
      c << "          {\"" << mem.name << "\", " << TypeExpr(mem.type) << ", "
        << (mem.key ? "true" : "false") << "},\n";
    }
    c << "      }},\n";
  }
  c << "  };\n  return structs;\n}\n\n"
    << "const std::vector<Enum>& Enums() {\n"
    << "  static const std::vector<Enum> enums = {\n";
  for (const auto& e : m.enums) {
    c << "      {\"" << e.name << "\", \"" << e.file << "\", {";
    for (std::size_t i = 0; i < e.enumerators.size(); ++i) {
      c << (i ? ", " : "") << "\"" << e.enumerators[i] << "\"";
    }
    c << "}},\n";
  }
  c << "  };\n  return enums;\n}\n\n"
    << "const Struct* FindStruct(std::string_view name) {\n"
    << "  for (const auto& s : Structs()) {\n    if (s.name == name) return &s;\n  }\n"
    << "  return nullptr;\n}\n\n"
    << "const Enum* FindEnum(std::string_view name) {\n"
    << "  for (const auto& e : Enums()) {\n    if (e.name == name) return &e;\n  }\n"
    << "  return nullptr;\n}\n\n"
    << "}  // namespace stickrep::idl\n";
  return c.str();
}

// Writes through a temporary file, so that a failed run leaves no partial output.
void WriteFile(const fs::path& path, const std::string& text) {
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, path);
}

int Usage() {
  std::cerr << "usage: idl_json_gen --header OUT.h --source OUT.cpp [-I DIR]... FILE.idl...\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  fs::path header, source;
  std::vector<fs::path> include_dirs, inputs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--header" || a == "--source" || a == "-I") && i + 1 < argc) {
      const std::string v = argv[++i];
      if (a == "--header") header = v;
      if (a == "--source") source = v;
      if (a == "-I") include_dirs.emplace_back(v);
    } else if (a.size() > 2 && a.compare(0, 2, "-I") == 0) {
      include_dirs.emplace_back(a.substr(2));
    } else if (!a.empty() && a[0] == '-') {
      return Usage();
    } else {
      inputs.emplace_back(a);
    }
  }
  if (header.empty() || source.empty() || inputs.empty()) return Usage();
  try {
    Model model;
    Parser parser(model, include_dirs);
    for (const auto& f : inputs) parser.ParseFile(f, "");
    if (model.structs.empty()) throw std::runtime_error("the IDL files define no struct");
    WriteFile(header, EmitHeader(model));
    WriteFile(source, EmitSource(model));
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
