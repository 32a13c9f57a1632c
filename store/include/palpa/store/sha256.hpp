#pragma once
// SHA-256 (OpenSSL's libcrypto) as 64 lower-case hex digits, the form the server's
// encode(sha256(bytea), 'hex') gives, so the two can be compared as text.
#include <filesystem>
#include <string>
#include <string_view>

namespace palpa::store {

std::string sha256_hex(std::string_view bytes);

/// The whole file's bytes; throws StoreError (not unreachable) naming the file.
std::string read_file_bytes(const std::filesystem::path& path);

}  // namespace palpa::store
