// Errors the user can act on. A ConfigError names the file, the key and what
// was expected; its what() is the whole message, ready to print.
#pragma once

#include <stdexcept>
#include <string>

namespace candela {

class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string file, std::string key, std::string expected)
      : std::runtime_error(format(file, key, expected)),
        file_(std::move(file)),
        key_(std::move(key)),
        expected_(std::move(expected)) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& expected() const { return expected_; }

 private:
  static std::string format(const std::string& f, const std::string& k, const std::string& e) {
    std::string s = f;
    if (!k.empty()) s += ": " + k;
    return s + ": " + e;
  }
  std::string file_, key_, expected_;
};

// Something the graphics stack or the OS refused; the message says what.
class RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace candela
