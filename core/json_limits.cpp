#include "json_limits.h"

#include <vector>

#include "shadowcts/errors.h"

namespace shadowcts {

void check_json_nesting(std::string_view text, const std::string& source,
                        const std::string& element, std::size_t max_depth) {
  std::size_t depth = 0, line = 1;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (c == '\n') ++line;
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) {
        throw InputError(source, element,
                         "nesting deeper than " + std::to_string(max_depth) +
                             " levels of arrays/objects (line " + std::to_string(line) + ")");
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

namespace {

// A scalar as JSON text, long strings cut first so that nothing large is copied.
std::string scalar_text(const nlohmann::json& value, std::size_t limit) {
  if (value.is_string()) {
    const std::string& s = value.get_ref<const std::string&>();
    return nlohmann::json(s.size() > limit ? s.substr(0, limit) : s).dump();
  }
  return value.dump();
}

}  // namespace

std::string describe_json(const nlohmann::json& value, std::size_t limit) {
  std::string text;
  struct Frame {
    const nlohmann::json* container;
    nlohmann::json::const_iterator next;
  };
  std::vector<Frame> open;
  auto emit = [&](const nlohmann::json& v) {
    if (v.is_object() || v.is_array()) {
      text += v.is_object() ? '{' : '[';
      open.push_back({&v, v.cbegin()});
    } else {
      text += scalar_text(v, limit);
    }
  };
  emit(value);
  while (!open.empty() && text.size() <= limit) {
    Frame& frame = open.back();
    const bool object = frame.container->is_object();
    if (frame.next == frame.container->cend()) {
      text += object ? '}' : ']';
      open.pop_back();
      continue;
    }
    if (frame.next != frame.container->cbegin()) text += ',';
    const nlohmann::json& child = *frame.next;
    if (object) text += scalar_text(nlohmann::json(frame.next.key()), limit) + ':';
    ++frame.next;  // before emit(): it may grow `open` and invalidate `frame`
    emit(child);
  }
  if (text.size() > limit) text = text.substr(0, limit > 3 ? limit - 3 : 0) + "...";
  return std::string(value.type_name()) + " " + text;
}

}  // namespace shadowcts
