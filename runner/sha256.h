#pragma once
// SHA-256 (OpenSSL's libcrypto) for the certificate: of files, of byte strings, incrementally.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace shadowcts {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(const void* data, std::size_t size);
  void update(std::string_view bytes) { update(bytes.data(), bytes.size()); }
  // 64 lower-case hex digits; the object is spent after it.
  std::string hex_digest();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

std::string sha256_hex(std::string_view bytes);

// Throws InputError naming the file when it cannot be read.
std::string sha256_file(const std::filesystem::path& path);

}  // namespace shadowcts
