#pragma once

// The one way a program prints the options it runs with, once at start-up: every field of an
// options struct and of the options nested in it, as indented "name: value" lines (YAML's
// shape, so the text can be pasted into a file and read back by eye).
//
//   struct TilingOptions {
//     double tile_size = 10.0;
//     void Describe(OptionsPrinter& out) const { out.Add("tile_size", tile_size); }
//   };
//   spdlog::info("options:\n{}", DescribeOptions(options));
//
// Each options struct has `void Describe(OptionsPrinter&) const` beside its `Status Validate()
// const`; a struct that holds other options calls Nested() on them.

#include <charconv>
#include <chrono>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

namespace fleetmap {

class OptionsPrinter {
 public:
  template <typename T>
  void Add(std::string_view name, const T& value) {
    Line(name, Format(value));
  }

  template <typename Options>
  void Nested(std::string_view name, const std::optional<Options>& options) {
    if (options) {
      Nested(name, *options);
    } else {
      Line(name, "none");
    }
  }

  template <typename Options>
  void Nested(std::string_view name, const Options& options) {
    Line(name, "");
    indent_ += 2;
    options.Describe(*this);
    indent_ -= 2;
  }

  const std::string& text() const { return text_; }

 private:
  template <typename T>
  struct IsDuration : std::false_type {};
  template <typename Rep, typename Period>
  struct IsDuration<std::chrono::duration<Rep, Period>> : std::true_type {};
  template <typename T>
  struct IsOptional : std::false_type {};
  template <typename T>
  struct IsOptional<std::optional<T>> : std::true_type {};

  template <typename T>
  static std::string Format(const T& value) {
    if constexpr (std::is_same_v<T, bool>) {
      return value ? "true" : "false";
    } else if constexpr (std::is_arithmetic_v<T>) {
      char buffer[64];
      const auto end = std::to_chars(buffer, buffer + sizeof(buffer), value).ptr;
      return std::string(buffer, end);  // shortest form that reads back: 0.05, not 0.0500000001
    } else if constexpr (std::is_enum_v<T>) {
      return Format(static_cast<std::underlying_type_t<T>>(value));
    } else if constexpr (IsDuration<T>::value) {
      return Format(std::chrono::duration<double>(value).count()).append(" s");
    } else if constexpr (IsOptional<T>::value) {
      return value ? Format(*value) : "none";
    } else if constexpr (requires { value.x() + value.y(); }) {  // a point (Eigen)
      return List({Format(value.x()), Format(value.y())});
    } else if constexpr (requires { value.x + value.y + value.yaw; }) {  // a Pose2
      return List({Format(value.x), Format(value.y), Format(value.yaw)});
    } else if constexpr (requires { std::string_view(value.value); }) {  // a strong id
      return Quoted(value.value);
    } else if constexpr (requires { value.begin()->second; }) {  // a map
      std::string text("{");
      for (const auto& [key, item] : value) {
        if (text.size() > 1) text.append(", ");
        text.append(Format(key)).append(": ").append(Format(item));
      }
      return text.append("}");
    } else {
      return Quoted(std::string_view(value));
    }
  }

  // "[a, b, c]". (Appends, not operator+: GCC 12 warns falsely on literal + std::string.)
  static std::string List(std::initializer_list<std::string> items) {
    std::string text("[");
    for (const std::string& item : items) {
      if (text.size() > 1) text.append(", ");
      text.append(item);
    }
    return text.append("]");
  }

  static std::string Quoted(std::string_view text) {
    return text.empty() ? "\"\"" : std::string(text);
  }

  void Line(std::string_view name, std::string_view value) {
    text_.append(indent_, ' ').append(name).append(":");
    if (!value.empty()) text_.append(" ").append(value);
    text_.append("\n");
  }

  int indent_ = 0;
  std::string text_;
};

// The text of `options`, which has `void Describe(OptionsPrinter&) const`.
template <typename Options>
std::string DescribeOptions(const Options& options) {
  OptionsPrinter printer;
  options.Describe(printer);
  return printer.text();
}

}  // namespace fleetmap
