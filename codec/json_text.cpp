#include "codec/json_text.h"

#include <set>
#include <string>
#include <vector>

namespace spinfold {

namespace {

struct TooDeep {};
struct DuplicateKey {
  std::string path;
};

// The members seen in each open object and the path to it, as the parser walks the text: a key
// met twice in one object is a DuplicateKey (its dotted path; [i] for array elements).
class KeyTracker {
 public:
  bool on(int depth, nlohmann::json::parse_event_t event, const nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    if (depth > kMaxJsonDepth) throw TooDeep{};
    switch (event) {
      case Event::object_start: open_.push_back({path_of_value(), {}, {}, false}); break;
      case Event::array_start: open_.push_back({path_of_value(), {}, {}, true}); break;
      case Event::key: {
        Open& o = open_.back();
        o.key = parsed.get<std::string>();
        if (!o.keys.insert(o.key).second) throw DuplicateKey{join(o.path, o.key)};
        return true;
      }
      case Event::object_end:
      case Event::array_end:
        open_.pop_back();
        advance();
        break;
      case Event::value: advance(); break;
    }
    return true;
  }

 private:
  struct Open {
    std::string path;
    std::set<std::string> keys;
    std::string key;  // the member being read (objects)
    bool array = false;
    std::size_t index = 0;  // the element being read (arrays)
  };
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  // The path of the value about to be read: the open object's current key, the open array's index.
  std::string path_of_value() const {
    if (open_.empty()) return "";
    const Open& o = open_.back();
    return o.array ? o.path + "[" + std::to_string(o.index) + "]" : join(o.path, o.key);
  }
  void advance() {
    if (!open_.empty() && open_.back().array) ++open_.back().index;
  }
  std::vector<Open> open_;
};

}  // namespace

nlohmann::json parse_json_text(std::string_view text) {
  // JSON text holds no raw NUL: outside strings only whitespace, inside them control characters
  // must be escaped.
  if (const std::size_t at = text.find('\0'); at != std::string_view::npos)
    throw JsonTextError("malformed JSON: a NUL byte at byte " + std::to_string(at) +
                        " (JSON text cannot contain one)");
  try {
    KeyTracker keys;
    const nlohmann::json::parser_callback_t check = [&keys](int depth, nlohmann::json::parse_event_t event,
                                                            nlohmann::json& parsed) {
      return keys.on(depth, event, parsed);
    };
    // strict (the default): a second value or anything but whitespace after the first is an error.
    return nlohmann::json::parse(text, check, true, false);
  } catch (const TooDeep&) {
    throw JsonTextError("JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  } catch (const DuplicateKey& d) {
    throw JsonTextError(
        "appears twice in one object: a key must be unique (RFC 8259 leaves a repeated key's "
        "meaning to each reader; I-JSON, RFC 7493, forbids it)",
        d.path);
  } catch (const nlohmann::json::exception& e) {
    throw JsonTextError(std::string("malformed JSON: ") + e.what());
  }
}

}  // namespace spinfold
