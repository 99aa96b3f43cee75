#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace stickrep::sensing {

// Why a sensing computation produced no value. Bad inputs are reported, never turned into
// a NaN width (SPEC §7).
enum class SensingError {
  kBadSonarRange,       // NaN, infinite, negative or outside the ring's 1-35 ft
  kBadFootprint,        // NaN, outside the image, or LJ >= RJ
  kStareOutOfRange,     // theta outside the geometry's valid interval (§5.3)
  kBadParameter,        // a non-physical parameter (door width <= 0, FOV, ...)
  kDegenerateGeometry,  // the triangles of §5.2 collapse (ray parallel to the wall)
  kNoValidSonar,        // the sensors a geometry needs are all invalid
  kOutsideEveryClass,   // no candidate width falls inside a door class (§4.1.2)
  kNoCandidate,         // no candidate footprint pair above the confidence threshold
  kOpenDoorUnresolved,  // depth edge inside the door but too few flank readings (§4.1.2)
};

const char* ToString(SensingError e);

// A value or the reason there is none: the error type of every sensing computation.
template <typename T>
class Result {
 public:
  static Result Ok(T value) { return Result(std::move(value)); }
  static Result Fail(SensingError error, std::string message) {
    return Result(error, std::move(message));
  }

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  const T& value() const {
    assert(ok());
    return *value_;
  }
  const T& operator*() const { return value(); }
  const T* operator->() const { return &value(); }
  // Meaningful only when !ok().
  SensingError error() const { return error_; }
  const std::string& message() const { return message_; }

 private:
  explicit Result(T value) : value_(std::move(value)) {}
  Result(SensingError error, std::string message) : error_(error), message_(std::move(message)) {}

  std::optional<T> value_;
  SensingError error_ = SensingError::kBadParameter;
  std::string message_;
};

}  // namespace stickrep::sensing
