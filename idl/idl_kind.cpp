#include "idl_json.h"

namespace stickrep::idl {

const char* KindSpelling(Kind kind) {
  switch (kind) {
    case Kind::kBoolean:
      return "boolean";
    case Kind::kOctet:
      return "octet";
    case Kind::kChar:
      return "char";
    case Kind::kShort:
      return "short";
    case Kind::kUnsignedShort:
      return "unsigned short";
    case Kind::kLong:
      return "long";
    case Kind::kUnsignedLong:
      return "unsigned long";
    case Kind::kLongLong:
      return "long long";
    case Kind::kUnsignedLongLong:
      return "unsigned long long";
    case Kind::kFloat:
      return "float";
    case Kind::kDouble:
      return "double";
    case Kind::kString:
      return "string";
    case Kind::kEnum:
      return "enum";
    case Kind::kStruct:
      return "struct";
    case Kind::kSequence:
      return "sequence";
    case Kind::kArray:
      return "array";
  }
  return "?";
}

}  // namespace stickrep::idl
