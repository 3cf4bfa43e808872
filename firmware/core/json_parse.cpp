#include "core/json_parse.h"

#include "core/error.h"

namespace candela {
namespace json_detail {
namespace {

// Counts nesting while nlohmann_json's SAX parser reads the text, and stops
// it (returns false) at the first array or object one level too deep.
class DepthCheck : public nlohmann::json_sax<nlohmann::json> {
 public:
  explicit DepthCheck(int max_depth) : max_(max_depth) {}
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return enter(); }
  bool key(string_t&) override { return true; }
  bool end_object() override { return leave(); }
  bool start_array(std::size_t) override { return enter(); }
  bool end_array() override { return leave(); }
  // Where and what, never the text itself: nlohmann's message ends with the
  // token it read ("last read: '...'"), a piece of a file that may not be
  // the sender's to see (an MQTT or socket client naming a file).
  bool parse_error(std::size_t position, const std::string&,
                   const nlohmann::detail::exception& e) override {
    std::string what = e.what();
    const size_t tag = what.find("] ");
    if (what.rfind("[json.exception", 0) == 0 && tag != std::string::npos) what.erase(0, tag + 2);
    const size_t echo = what.find("; last read:");
    if (echo != std::string::npos) what.erase(echo);
    error_ = "not valid JSON (byte " + std::to_string(position) + "): " + what;
    return false;
  }
  const std::string& error() const { return error_; }
  bool too_deep() const { return too_deep_; }

 private:
  bool enter() {
    if (++depth_ > max_) {
      too_deep_ = true;
      return false;
    }
    return true;
  }
  bool leave() {
    --depth_;
    return true;
  }
  int max_;
  int depth_ = 0;
  bool too_deep_ = false;
  std::string error_;
};

}  // namespace

std::string check_depth(std::string_view text, int max_depth) {
  DepthCheck check(max_depth);
  const bool ok = nlohmann::json::sax_parse(text, &check, nlohmann::json::input_format_t::json,
                                            /*strict=*/true, /*ignore_comments=*/false);
  if (check.too_deep())
    return "expected JSON nested at most " + std::to_string(max_depth) +
           " arrays or objects deep, got deeper";
  if (!check.error().empty()) return check.error();
  if (!ok) return "not valid JSON";
  return "";
}

}  // namespace json_detail

nlohmann::json parse_json(std::string_view text, const std::string& file, const std::string& key,
                          int max_depth) {
  std::string error;
  std::optional<nlohmann::json> j = try_parse_json(text, &error, max_depth);
  if (!j) throw ConfigError(file, key, error);
  return std::move(*j);
}

}  // namespace candela
