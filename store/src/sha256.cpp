#include "palpa/store/sha256.hpp"

#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <openssl/evp.h>

#include "palpa/store/pg.hpp"

namespace palpa::store {

std::string sha256_hex(std::string_view bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr) != 1) {
    throw StoreError("store: sha-256: libcrypto failed", false);
  }
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

std::string read_file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw StoreError(fmt::format("{}: cannot be opened for reading", path.string()), false);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw StoreError(fmt::format("{}: read error", path.string()), false);
  return std::move(bytes).str();
}

}  // namespace palpa::store
