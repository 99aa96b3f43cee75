#pragma once

// What the generated JSON form of the IDL types (msgs_json.h, written by idl_json_gen at build
// time) is made of: the description of an IDL type, the error from_json throws, and base64
// for octet sequences.

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace stickrep::idl {

// The IDL types idl_json_gen understands.
enum class Kind {
  kBoolean,
  kOctet,
  kChar,
  kShort,
  kUnsignedShort,
  kLong,
  kUnsignedLong,
  kLongLong,
  kUnsignedLongLong,
  kFloat,
  kDouble,
  kString,
  kEnum,
  kStruct,
  kSequence,
  kArray,
};

// A kind as IDL spells it: "unsigned long", "string", ... ("enum", "struct", "sequence",
// "array" for the constructed kinds). Shared by the generator and the type description.
const char* KindSpelling(Kind kind);

// The type of a struct member (or of a sequence's or an array's elements).
struct Type {
  Kind kind = Kind::kBoolean;
  std::string idl;   // as IDL spells it, with scoped names: "sequence<stickrep::msgs::MapEdge>"
  std::string name;  // an enum's or a struct's scoped name, e.g. "stickrep::msgs::Pose2D"
  std::uint32_t bound = 0;  // a sequence's or a string's bound (0: unbounded); an array's length
  std::shared_ptr<const Type> element;  // of a sequence or an array
};

struct Member {
  std::string name;
  Type type;
  bool key = false;  // @key
};

struct Struct {
  std::string name;  // scoped: "stickrep::msgs::SonarScan"
  std::string file;  // the .idl file that defines it
  std::vector<Member> members;
};

struct Enum {
  std::string name;  // scoped: "stickrep::msgs::MotionMode"
  std::string file;
  std::vector<std::string> enumerators;  // in order: the first has value 0
};

// Type descriptions, as the generated code builds them.
Type BasicType(Kind kind);
Type NamedType(Kind kind, std::string scoped_name);  // kEnum or kStruct
Type StringType(std::uint32_t bound);
Type SequenceType(Type element, std::uint32_t bound);
Type ArrayType(Type element, std::uint32_t length);

// A JSON document that is not the JSON form of the type it is read as.
class JsonFormError : public std::runtime_error {
 public:
  JsonFormError(std::string path, std::string reason);
  // Where in the document: "best.pose.x_in", "hypotheses[3].ring_id"; empty for the top.
  const std::string& path() const { return path_; }
  const std::string& reason() const { return reason_; }
  // The same error one level up: `step` is a member name or "[i]".
  JsonFormError Within(const std::string& step) const;

 private:
  std::string path_;
  std::string reason_;
};

// Standard base64 (RFC 4648, with padding).
std::string Base64Encode(const std::vector<std::uint8_t>& bytes);
// Throws JsonFormError on anything but canonical padded base64.
std::vector<std::uint8_t> Base64Decode(std::string_view text);

// For visiting the generated types: ForEachStruct(visitor) calls visitor(TypeTag<T>{}, ...).
template <typename T>
struct TypeTag {
  using type = T;
};

// The scoped IDL name of a type, TypeName<T>::value; msgs_json.h specialises it for every
// struct and enum.
template <typename T>
struct TypeName;

}  // namespace stickrep::idl
